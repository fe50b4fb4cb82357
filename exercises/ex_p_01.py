"""P-01 Spindle reversal CW -> CCW with time limits (the PLC836 mechanisms chapter's CWCCW, seed 003 §4.3).
Plant: SPINDLE.

The chapter's task: reverse the spindle with a mechanism CWCCW; if the contact of SMP does not drop within
1 s report error 4.04; if the contact of SMN does not close within 1 s switch the contactor off and report
4.05. Its first version (EX1/EX0, no limits) and two slips the chapter warns about are the wrong programs:
no 0.2 s pause, and the polarity of TEX0/TEX1 (the digit names the value that blocks).
"""

from exercises._common import solution
from exercises._mechanisms import mech_solution, spindle, spindle_io
from plcsim.check import all_of, becomes, falls, holds, never, rises, value
from plcsim.exercise import Exercise, only
from plcsim.scenario import FAULTS, Scenario, jam_motor, press, stuck, write

NUMBER = "P-01"
SMP_OFF = "SMP is switched off within 2 scans after REV is pressed"
NO_OVERLAP = "SMN is never on while KSMP is closed"
PAUSE = "SMN is switched on 0.2 s after KSMP opens (at most 2 scans later)"
ERROR_4 = "a KSMP that stays closed: BZH11 = 4 1 s after REV (to within 3 scans)"
ERROR_5 = "an SMN that never closes: BZH11 = 5 1 s after SMN is switched on (to within 3 scans)"
SMN_OFF = "an SMN that never closes is switched off again 1 s after it was switched on (to within 3 scans)"
SMN_STAYS = "after a reversal SMN stays on"
NO_ERROR = "BZH11 stays 0 in a reversal that succeeds"

# the words of the task each check grades (.grades)
SMP_OFF_WORDS = "switch SMP off (within 2 scans of the press)"
PAUSE_WORDS = "wait until KSMP opens; switch SMN on 0.2 s later (not sooner, and at most 2 scans later)"
SMN_STAYS_WORDS = "wait until KSMN closes, and end, leaving SMN on"
NO_OVERLAP_WORDS = "SMN is never on while KSMP is closed"
ERROR_4_WORDS = (
    "If KSMP does not open within 1 s, store 4 in BZH11 (error 4.04) 1 s after the press (to within 3 scans)"
)
ERROR_5_WORDS = (
    "If KSMN does not close within 1 s of switching SMN on (the contactor does not pick up), switch SMN off "
    "and store 5 in BZH11 (error 4.05), both 1 s after SMN was switched on (to within 3 scans)"
)
NO_ERROR_WORDS = "A reversal that succeeds leaves BZH11 at 0"


def _reversal(name: str, *faults, description: str, fault_words: str = "") -> Scenario:
    """The reversal of the spindle running clockwise, with ``faults`` (stated in the task's ``fault_words``)."""
    return Scenario(
        name,
        write("SMP", True, t="0ms"),
        *press("REV", t="1s..1.5s", hold="50ms..150ms"),
        *faults,
        outside={FAULTS: fault_words} if faults else None,
        duration="3s",
        description=description,
    )


EXERCISE = Exercise(
    number=NUMBER,
    slug="mechanism-spindle-reversal",
    title="Spindle reversal CW -> CCW with time limits (PLC836 mechanism CWCCW)",
    title_sk="Reverzace otáček vřetena CW -> CCW s časovými limity (mechanismus CWCCW)",
    task=(
        "The spindle runs clockwise: the motor-positive contactor SMP is on. Its auxiliary contact KSMP and the "
        "contact KSMN of the motor-negative contactor SMN are wired to inputs (closed = TRUE); they follow "
        "their coils after 30..40 ms. Write a mechanism CWCCW (a .mech file, or MECHANISM() in Python) that "
        "pressing REV starts and that reverses the spindle: switch SMP off (within 2 scans of the press); wait "
        "until KSMP opens; switch SMN on 0.2 s later (not sooner, and at most 2 scans later); wait until KSMN "
        "closes, and end, leaving SMN on. SMN is never on while KSMP is closed. If KSMP does not open within "
        "1 s, store 4 in BZH11 (error 4.04) 1 s after the press (to within 3 scans). If KSMN does not close "
        "within 1 s of switching SMN on (the contactor does not pick up), switch SMN off and store 5 in BZH11 "
        "(error 4.05), both 1 s after SMN was switched on (to within 3 scans). A reversal that succeeds leaves "
        "BZH11 at 0. CWCCW ends after an error too."
    ),
    io=spindle_io("REV", "reverse push-button"),
    rig=spindle,
    scenarios=[
        _reversal("reversal", description="the spindle running clockwise is reversed"),
        _reversal(
            "KSMP stuck",
            stuck("KSMP", True, t="0ms"),
            fault_words="If KSMP does not open within 1 s",
            description="the contact of SMP is stuck closed (a welded contact or a short on its wire)",
        ),
        _reversal(
            "SMN never closes",
            jam_motor("SMN", t="0ms"),
            fault_words="If KSMN does not close within 1 s of switching SMN on (the contactor does not pick up)",
            description="the motor-negative contactor never picks up",
        ),
    ],
    checks=[
        falls("SMP").within("2 scans").after(rises("REV")).named(SMP_OFF).grades(SMP_OFF_WORDS),
        never(all_of("SMN", "KSMP")).named(NO_OVERLAP).grades(NO_OVERLAP_WORDS),
        only(
            rises("SMN").between("200ms", "200ms + 2 scans").after(falls("KSMP")).named(PAUSE).grades(PAUSE_WORDS),
            "reversal",
        ),
        only(never(value("BZH11") != 0).named(NO_ERROR).grades(NO_ERROR_WORDS), "reversal"),
        only(holds("SMN").to_the_end().named(SMN_STAYS).grades(SMN_STAYS_WORDS), "reversal"),
        only(
            becomes(value("BZH11") == 4)
            .between("1s - 3 scans", "1s + 3 scans")
            .after(rises("REV"))
            .named(ERROR_4)
            .grades(ERROR_4_WORDS),
            "KSMP stuck",
        ),
        only(
            becomes(value("BZH11") == 5)
            .between("1s - 3 scans", "1s + 3 scans")
            .after(rises("SMN"))
            .named(ERROR_5)
            .grades(ERROR_5_WORDS),
            "SMN never closes",
        ),
        only(
            falls("SMN")
            .between("1s - 3 scans", "1s + 3 scans")
            .after(rises("SMN"))
            .named(SMN_OFF)
            .grades(ERROR_5_WORDS),
            "SMN never closes",
        ),
    ],
    solutions=[
        mech_solution(NUMBER, "reference", explanation="the chapter's CWCCW with TEX1/TIM/TEX0 and CW_ERR, verbatim"),
        solution(NUMBER, "python-form", "alternative", "the same mechanism in the Python form"),
        mech_solution(
            NUMBER,
            "wrong-no-limits",
            "wrong",
            "the chapter's first CWCCW (EX1/EX0): a contact that never moves holds the mechanism for ever, and no "
            "error is reported",
            fails=(ERROR_4, ERROR_5, SMN_OFF),
        ),
        mech_solution(
            NUMBER,
            "wrong-no-delay",
            "wrong",
            "no TIM: SMN is switched on in the scan that sees KSMP open, with no pause for the arc to die",
            fails=(PAUSE,),
        ),
        mech_solution(
            NUMBER,
            "wrong-polarity",
            "wrong",
            "TEX1 for 'wait until KSMN closes': TEX1 blocks while the condition is 1, so with KSMN open it "
            "passes at once: CWCCW ends before the contactor has closed and misses one that never closes",
            fails=(ERROR_5, SMN_OFF),
        ),
    ],
    notes=(
        "The chapter's D1 = 50 and D02 = 10 are read as 20 ms counts (1 s, 0.2 s), the only unit all three of "
        "its examples agree on. The spindle starts clockwise by an HMI write of SMP at 0 s."
    ),
)
