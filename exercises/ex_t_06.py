"""T-06 The hydraulic feed slide (the manual's EX-19, SET/RES and a TON on the 1 s base). Plant: SLIDE.

The manual (§7.5.3, example 2): "After START1 and START2 are pressed together, one working cycle is executed
... At limit switch K5 the slide waits 5 s. A new start is possible only from the initial position (K1)." Its
program implements neither the STOP button nor the speed valve EM3, and leaves K2..K4 unused (gap G18 of
``spec/tecomat.md``: "test only what the program does"); so does this exercise.
"""

from exercises._tecomat import il_solution
from plants.slide import Slide
from plcsim.check import all_of, always, count, event, falls, holds, implies, never, rises
from plcsim.exercise import IO, Exercise, only
from plcsim.scenario import Scenario, press

NUMBER = "T-06"
STARTS = "EM1 opens in the cycle that sees START1 and START2 pressed together at K1"
ONCE = "EM1 opens once per working cycle: a start away from K1 is refused"
AT_K5 = "EM1 closes in the cycle that sees K5"
DWELL = "EM2 opens 5 s after the slide reaches K5 (+ 1 cycle)"
LATCHED = "EM2 stays open from K5 back to K1"
AT_K1 = "EM2 closes in the cycle that sees K1"
APART = "EM1 and EM2 are never open together"


def two_hand_start(t_ms: int) -> list:
    """START1 and START2 pressed at seeded instants, held long enough to overlap (one may lead by 0.5 s)."""
    return [
        *press("start1", t=f"{t_ms}ms..{t_ms + 300}ms", hold="800ms..1s"),
        *press("start2", t=f"{t_ms + 500}ms..{t_ms + 700}ms", hold="300ms..500ms"),
    ]


EXERCISE = Exercise(
    number=NUMBER,
    slug="tecomat-feed-slide",
    title="Hydraulic feed slide (Tecomat EX-19)",
    title_sk="Tecomat, příklad EX-19 – hydraulický suport",
    task=(
        "A hydraulic feed slide is moved by the solenoid valves em1 (forward, Y0.0) and em2 (backward, Y0.1); the "
        "limit switch k1 (X0.2) marks its initial position, k5 (X0.3) the end of the working stroke. When the "
        "push-buttons start1 (X0.0) and start2 (X0.1) are pressed together while the slide is at k1, it runs one "
        "working cycle: forward to k5, a wait of 5 s there, back to k1. A start is possible only from k1. Each "
        "valve opens and closes in the cycle that sees its condition (em2 at most one cycle after the 5 s), and em1 "
        "and em2 are never open together. Write "
        "it in the Tecomat's instruction list with SET/RES and a TON on the 1 s time base (code .2). The STOP "
        "button and the speed valve em3 of the manual's task are left out, as its program leaves them out."
    ),
    io=[
        IO("start1", "start push-button 1 (two-hand start)", "Bool", "%I0.0", "NO", comment="X0.0 as in EX-19"),
        IO("start2", "start push-button 2", "Bool", "%I0.1", "NO", comment="X0.1 as in EX-19"),
        IO("k1", "limit switch: initial position", "Bool", "%I0.2", "NO", comment="X0.2 as in EX-19"),
        IO("k5", "limit switch: end of the working stroke", "Bool", "%I0.3", "NO", comment="X0.3 as in EX-19"),
        IO("em1", "valve EM1: forward", "Bool", "%Q0.0", comment="Y0.0 as in EX-19"),
        IO("em2", "valve EM2: backward", "Bool", "%Q0.1", comment="Y0.1 as in EX-19"),
    ],
    rig=Slide,
    cpu={"cycle": "10ms"},
    dt="10ms",
    scenarios=[
        Scenario(
            "one working cycle",
            *two_hand_start(500),
            duration="18s",
            description="a two-hand start at k1: forward, 5 s at k5, back to k1",
        ),
        Scenario(
            "starts refused",
            *press("start1", t="300ms..500ms", hold="200ms..400ms"),
            *press("start2", t="1s..1.2s", hold="200ms..400ms"),
            *two_hand_start(2000),
            *two_hand_start(9500),
            *two_hand_start(15000),
            duration="24s",
            description="each button alone, a two-hand start at k1, and two more: while the slide waits at k5 "
            "and on its way back",
        ),
    ],
    checks=[
        always(implies(all_of("start1", "start2", "k1"), "em1")).named(STARTS),
        count(rises("em1")).equals(1).named(ONCE),
        falls("em1").within("1 scan").after(rises("k5")).named(AT_K5),
        rises("em2").between("5s", "5s + 2 scans").after(rises("k5")).named(DWELL),
        holds("em2").until(rises("k1")).named(LATCHED),
        falls("em2").within("1 scan").after(rises("k1")).named(AT_K1),
        never(all_of("em1", "em2")).named(APART),
        only(never(event("interlock violated")).named("the two valves never fight"), "starts refused"),
    ],
    requirements={
        "EM1 opens in the cycle that sees START1 and START2 pressed together at K1": (
            "Each valve opens and closes in the cycle that sees its condition"
        ),
        "EM1 opens once per working cycle: a start away from K1 is refused": "A start is possible only from k1",
        "EM1 closes in the cycle that sees K5": "Each valve opens and closes in the cycle that sees its condition",
        "EM2 opens 5 s after the slide reaches K5 (+ 1 cycle)": "em2 at most one cycle after the 5 s",
        "EM2 stays open from K5 back to K1": "forward to k5, a wait of 5 s there, back to k1",
        "EM2 closes in the cycle that sees K1": "Each valve opens and closes in the cycle that sees its condition",
        "EM1 and EM2 are never open together": "em1 and em2 are never open together",
        "the two valves never fight": "em1 and em2 are never open together",
    },
    solutions=[
        il_solution(NUMBER, "reference", explanation="EX-19 as printed: SET em1 at k1, RES at k5; TON k5 5 s SETs em2"),
        il_solution(
            NUMBER,
            "wrong-start-anywhere",
            "wrong",
            "AND k1 left out: a two-hand start on the way back opens EM1 against EM2",
            fails=(ONCE, APART),
        ),
        il_solution(
            NUMBER,
            "wrong-em2-coil",
            "wrong",
            "WR em2 for SET: EM2 follows the timer's output and closes as soon as the slide leaves K5",
            fails=(LATCHED,),
        ),
        il_solution(
            NUMBER,
            "wrong-time-base",
            "wrong",
            "time base .1 (100 ms) for .2 (1 s): the slide waits 0.5 s at K5",
            fails=(DWELL,),
        ),
    ],
    notes=(
        "The slide takes 4.9 s from k1 to k5 at the working feed (40 mm/s) and as long back; with the timer's "
        "units counted from the cycle that sees k5 (setting timer_ticks), EM2 opens in the cycle 5 s later."
    ),
)
