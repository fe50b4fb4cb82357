"""4.3.20 Second program in OB30. Plant: PANEL. (Analysis exercise.)"""

from exercises._common import solution
from exercises._panel import OB30_CPU, OB30_IO, ob30_panel
from plcsim.check import eventually, holds, never, rises
from plcsim.exercise import IO, Exercise, only
from plcsim.scenario import Scenario, press

NUMBER = "4.3.20"
IN_OB30 = "enter the program in OB30 (networks in this order)"
"""What every check grades: the task's program entered in OB30, as the task gives it."""
FROM_0, AFTER_0, SHORT = "pressed from 0 s", "pressed after the 0 s call", "short presses, then a long one"

EXERCISE = Exercise(
    number=NUMBER,
    slug="ob30-2",
    title="Second program in OB30",
    title_sk="Príklad 20 – Druhý program v OB30",
    task=(
        "A program similar to 4.3.19 (Fig. 4.180) runs in OB30 with a period of 1 s; its execution takes about "
        "1 ms. Network 1: LED := START (the memory bit is copied to the output). Network 2: TL -> S START (the "
        "push-button TL, wired NO, sets START). The memory bit START (start flag) is initially FALSE. OB30 is "
        "called at the STOP->RUN instant (0 s), then at 1 s, 2 s ...\n"
        "Task: enter the program in OB30 (networks in this order) and analyse how the LED depends on TL for a "
        "press from 0 s and for a press from 0.1 s."
    ),
    io=[*OB30_IO, IO("START", "start flag, set by TL", "Bool", "%M10.0", comment="memory bit; address proposed")],
    rig=ob30_panel,
    cpu=OB30_CPU,
    scenarios=[
        Scenario(
            FROM_0,
            *press("TL", t="0s", hold="1.1s..2.5s"),
            duration="4.5s",
            description="case (a): TL pressed at STOP->RUN (0 s) and held 1.1..2.5 s",
        ),
        Scenario(
            AFTER_0,
            *press("TL", t="50ms..950ms", hold="1.1s..2s"),
            duration="4.5s",
            description="case (b): TL pressed just after the 0 s call (0.05..0.95 s), held past the 1 s call",
        ),
        Scenario(
            SHORT,
            *press("TL", t="50ms..300ms", hold="100ms..500ms"),
            *press("TL", t="1.05s..1.3s", hold="100ms..600ms"),
            *press("TL", t="2.05s..2.5s", hold="1.1s..1.3s"),
            duration="5.5s",
            description="two presses between calls, then one held over the 3 s call",
        ),
    ],
    checks=[
        only(eventually("START").before("1ms").named("pressed from 0 s: START is set by the call at 0 s"), FROM_0),
        only(
            never("LED").during("0s", "1s").named("pressed from 0 s: the LED stays off until the call at 1 s"),
            FROM_0,
        ),
        only(
            eventually(rises("LED")).before("1s + 2ms").named("pressed from 0 s: the LED lights at the call at 1 s"),
            FROM_0,
        ),
        only(
            never("START").during("0s", "1s").named("pressed after the 0 s call: START stays FALSE until 1 s"),
            AFTER_0,
        ),
        only(
            eventually(rises("START"))
            .before("1s + 1ms")
            .named("pressed after the 0 s call: START is set by the call at 1 s"),
            AFTER_0,
        ),
        only(
            never("LED")
            .during("0s", "2s")
            .named("pressed after the 0 s call: the LED stays off until the call at 2 s"),
            AFTER_0,
        ),
        only(
            eventually(rises("LED"))
            .before("2s + 2ms")
            .named("pressed after the 0 s call: the LED lights at the call at 2 s"),
            AFTER_0,
        ),
        only(never("START").during("0s", "3s").named("a press between two calls is never seen"), SHORT),
        only(
            eventually(rises("LED"))
            .before("4s + 2ms")
            .named("a press held over the 3 s call lights the LED at the call at 4 s"),
            SHORT,
        ),
        # Spec §2 4.3.20: "Rung 2: IF TL THEN S START"; "If the program runs while the button is pressed, START is
        # set; in the next execution START = TRUE is assigned to LED." START is set, never reset: once lit, the LED
        # stays lit. Each scenario lasts past the second call after the release, so START := TL as a coil lets the
        # LED go out before the end of every run.
        holds("LED").to_the_end().named("once lit, the LED stays lit (START is set, not assigned)"),
        rises("LED")
        .between("1s", "1s + 2ms")
        .after(rises("START"), at_least=0)
        .named("the LED follows START one call (1 s) later"),
    ],
    requirements={
        "pressed from 0 s: START is set by the call at 0 s": IN_OB30,
        "pressed from 0 s: the LED stays off until the call at 1 s": (
            "enter the program in OB30 (networks in this order)"
        ),
        "pressed from 0 s: the LED lights at the call at 1 s": IN_OB30,
        "pressed after the 0 s call: START stays FALSE until 1 s": IN_OB30,
        "pressed after the 0 s call: START is set by the call at 1 s": (
            "enter the program in OB30 (networks in this order)"
        ),
        "pressed after the 0 s call: the LED stays off until the call at 2 s": (
            "enter the program in OB30 (networks in this order)"
        ),
        "pressed after the 0 s call: the LED lights at the call at 2 s": (
            "enter the program in OB30 (networks in this order)"
        ),
        "a press between two calls is never seen": IN_OB30,
        "a press held over the 3 s call lights the LED at the call at 4 s": (
            "enter the program in OB30 (networks in this order)"
        ),
        "once lit, the LED stays lit (START is set, not assigned)": (
            "enter the program in OB30 (networks in this order)"
        ),
        "the LED follows START one call (1 s) later": IN_OB30,
    },
    solutions=[
        solution(NUMBER, "reference", explanation="LED := START, then TL -> S START, in OB30 (1 s)"),
        solution(
            NUMBER,
            "wrong-order",
            "wrong",
            "the networks swapped: LED := START sees the new START in the same call, one period early",
            fails=(
                "pressed from 0 s: the LED stays off until the call at 1 s",
                "pressed after the 0 s call: the LED stays off until the call at 2 s",
                "the LED follows START one call (1 s) later",
            ),
        ),
        solution(
            NUMBER,
            "wrong-coil",
            "wrong",
            "START := TL as a plain coil instead of S START: the LED follows the button one call late and goes out "
            "again after the release",
            fails=("once lit, the LED stays lit (START is set, not assigned)",),
        ),
    ],
    notes=(
        "The network order is reconstructed from the analysis ('the program runs top to bottom'). START is set "
        "during the call (memory, valid from the call's start); the LED written by the call at T reaches the "
        "output module at T + 1 ms, hence the windows 'T + 1 ms' / 'T + 2 ms'; 'stays off until the call at T' "
        "looks at every scan that starts before T. START is an %M bit, cleared at STOP->RUN. The textbook "
        "shows no wrong program; 'wrong-order' swaps the two networks. In the 'pressed from 0 s' scenario START "
        "is TRUE in the very first trace row, which has no predecessor to rise from, so 'the LED follows START' "
        "has nothing to check there (at_least=0); that case is covered by its own checks. The runs last 4.5 s "
        "(5.5 s): the press ends by 2.95 s (3.8 s), so a START that follows TL is FALSE at the call at 3 s (4 s) and "
        "the LED goes out at the call at 4 s (5 s), inside every run."
    ),
)
