"""P-02 Start a mechanism and wait for it, at most 10 s (the PLC836 mechanisms chapter, seed 003 §4.3).
Plant: SPINDLE.

The chapter's two listings start mechanism CW in the preparatory functions and wait for it to end, the
second at most 10 s with error 4.12. The chapter's own warning is the wrong program here: without the EX
after ``FL 1,CW`` the start lies in the window of the wait and runs again every scan, so CW is started
again as soon as it ends and the wait never ends. The chapter never gives CW; ours switches the spindle
on clockwise and retries a contactor that does not pick up (a looping mechanism, §3.9), so that a
counter shared between the two mechanisms (a timeout that never fires: each retry restarts it) is a
slip a program can make. The preparatory functions are a mechanism PREP of their own.
"""

from exercises._common import solution
from exercises._mechanisms import mech_solution, spindle, spindle_io
from plcsim.check import all_of, becomes, durations, falls, holds, never, off, rises, value
from plcsim.exercise import IO, Exercise, only
from plcsim.scenario import FAULTS, Scenario, jam_motor, press

NUMBER = "P-02"
FAULT_WORDS = "if it has not closed (the contactor does not pick up), switch SMP off"
"""The task's words for its fault scenarios (``Scenario(outside=...)``)."""
SMP_ON = "SMP is switched on within 2 scans after START is pressed"
READY = "READY lights within 2 scans after KSMP closes"
ERROR_12 = "a spindle that never starts: BZH11 = 18 (12H) 10 s after START (at most 3 scans later)"
READY_LATE = "READY stays off until KSMP closes"
NOT_READY = "a spindle that never starts: READY stays off"
NO_ERROR = "BZH11 stays 0 when the spindle starts"
NO_SHORT = "SMP and SMN are never on together"
RETRY_OFF = "a contactor that does not pick up: SMP off 2 s after it was switched on (to within 3 scans)"
RETRY_ON = "a contactor that does not pick up: SMP on again 0.5 s after it was switched off (to within 3 scans)"

# the words of the task each check grades (.grades)
SMP_ON_WORDS = "starts CW (SMP is on within 2 scans of the press)"
NO_SHORT_WORDS = "SMP and SMN are never on together"
READY_WORDS = "switches READY on (within 2 scans after KSMP closes)"
READY_LATE_WORDS = "READY stays off until KSMP closes"
NO_ERROR_WORDS = "A spindle that starts leaves BZH11 at 0"
ERROR_12_WORDS = (
    "If CW has not ended 10 s after the press, PREP stores 18 (12H, error 4.12) in BZH11 (10 s after the press "
    "at the earliest, at most 3 scans later)"
)
NOT_READY_WORDS = "leaving CW as it is and READY off"
RETRY_OFF_WORDS = (
    "if it has not closed (the contactor does not pick up), switch SMP off (2 s after switching it on, to within "
    "3 scans)"
)
RETRY_ON_WORDS = (
    "wait 0.5 s, switch SMP on again (0.5 s after switching it off, to within 3 scans) and wait again, as often "
    "as it takes"
)

EXERCISE = Exercise(
    number=NUMBER,
    slug="mechanism-start-and-wait",
    title="Start a mechanism and wait for it at most 10 s (PLC836 mechanisms PREP and CW)",
    title_sk="Spuštění mechanismu a čekání na jeho vykonání nejvýše 10 s",
    task=(
        "Write two mechanisms (a .mech file, or MECHANISM() in Python). CW switches the spindle on clockwise:"
        " switch SMN off, wait while its contact KSMN is closed, switch SMP on and wait until its contact "
        "KSMP closes, at most 2 s; if it has not closed (the contactor does not pick up), switch SMP off (2 s "
        "after switching it on, to within 3 scans), wait 0.5 s, switch SMP on again (0.5 s after switching it "
        "off, to within 3 scans) and wait again, as often as it takes; then end. SMP and SMN are never on "
        "together. PREP, started by the push-button START, switches the lamp READY off, starts CW (SMP is on "
        "within 2 scans of the press) and waits until CW has ended, then switches READY on (within 2 scans "
        "after KSMP closes) and ends; READY stays off until KSMP closes. If CW has not ended 10 s after the "
        "press, PREP stores 18 (12H, error 4.12) in BZH11 (10 s after the press at the earliest, at most 3 "
        "scans later) and ends, leaving CW as it is and READY off. A spindle that starts leaves BZH11 at 0."
    ),
    io=spindle_io("START", "start push-button", IO("READY", "lamp: the spindle has started", "Bool", "%Q0.2")),
    rig=spindle,
    scenarios=[
        Scenario(
            "start",
            *press("START", t="0.5s..1s", hold="50ms..150ms"),
            duration="3s",
            description="the spindle is started",
        ),
        Scenario(
            "SMP never closes",
            *press("START", t="0.5s..1s", hold="50ms..150ms"),
            jam_motor("SMP", t="0ms"),
            outside={FAULTS: FAULT_WORDS},
            duration="12s",
            description="the motor-positive contactor never picks up",
        ),
    ],
    checks=[
        rises("SMP").within("2 scans").after(rises("START")).named(SMP_ON).grades(SMP_ON_WORDS),
        never(all_of("SMP", "SMN")).named(NO_SHORT).grades(NO_SHORT_WORDS),
        only(rises("READY").within("2 scans").after(rises("KSMP")).named(READY).grades(READY_WORDS), "start"),
        only(holds(off("READY")).until(rises("KSMP")).named(READY_LATE).grades(READY_LATE_WORDS), "start"),
        only(never(value("BZH11") != 0).named(NO_ERROR).grades(NO_ERROR_WORDS), "start"),
        only(
            becomes(value("BZH11") == 18)
            .between("10s", "10s + 3 scans")
            .after(rises("START"))
            .named(ERROR_12)
            .grades(ERROR_12_WORDS),
            "SMP never closes",
        ),
        only(never("READY").named(NOT_READY).grades(NOT_READY_WORDS), "SMP never closes"),
        only(
            durations("SMP").between("2s - 3 scans", "2s + 3 scans").named(RETRY_OFF).grades(RETRY_OFF_WORDS),
            "SMP never closes",
        ),
        only(
            rises("SMP")
            .between("0.5s - 3 scans", "0.5s + 3 scans")
            .after(falls("SMP"))
            .named(RETRY_ON)
            .grades(RETRY_ON_WORDS),
            "SMP never closes",
        ),
    ],
    solutions=[
        mech_solution(NUMBER, "reference", explanation="the chapter's listing with TEX1 CITAC,D500,ERR1 and our CW"),
        solution(NUMBER, "python-form", "alternative", "the same mechanisms in the Python form"),
        mech_solution(
            NUMBER,
            "wrong-no-ex",
            "wrong",
            "no EX after FL 1,CW: the start is in the window of the wait and runs every scan, so CW starts "
            "again as soon as it ends and PREP waits for ever, READY stays off (the chapter's warning)",
            fails=(READY,),
        ),
        mech_solution(
            NUMBER,
            "wrong-no-timeout",
            "wrong",
            "EX1 instead of TEX1: a spindle that never starts holds PREP for ever and reports nothing",
            fails=(ERROR_12,),
        ),
        mech_solution(
            NUMBER,
            "wrong-shared-counter",
            "wrong",
            "CW's retry uses PREP's counter CITAC: every state that names a counter restarts it, so each retry "
            "(every 2.5 s) restarts PREP's 10 s and the timeout never fires",
            fails=(ERROR_12,),
        ),
        mech_solution(
            NUMBER,
            "wrong-polarity",
            "wrong",
            "TEX0 for 'wait while CW runs': TEX0 blocks while CW = 0, so PREP passes at once and lights READY "
            "before the spindle runs",
            fails=(READY_LATE, ERROR_12, NOT_READY),
        ),
    ],
    notes="D500 = 500 counts of 20 ms = 10 s (the chapter's own reading of its constant).",
    spec_equivalent={
        "line 19: EX → BEX": "BEX cuts the start of CW off the window of the wait without losing a scan, as the "
        "chapter says it does; the 10 s then count from one scan earlier, within the 3 scans the task allows",
    },
)
