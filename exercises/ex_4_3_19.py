"""4.3.19 First program in OB30. Plant: PANEL. (Analysis exercise.)"""

from exercises._common import solution
from exercises._panel import OB30_CPU, OB30_IO, ob30_panel
from plcsim.check import eventually, falls, never, rises
from plcsim.exercise import Exercise, only
from plcsim.scenario import Scenario, press

NUMBER = "4.3.19"
IN_OB30 = "Enter the program in OB30"
"""What every check grades: the task's program entered in OB30, as the task gives it."""
FROM_0, AFTER_0, SHORT = "pressed from 0 s", "pressed after the 0 s call", "short presses, then a long one"

EXERCISE = Exercise(
    number=NUMBER,
    slug="ob30-1",
    title="First program in OB30",
    title_sk="Príklad 19 – Prvý program v OB30",
    task=(
        "Exercises 4.3.19-4.3.22 run simple logic in the cyclic-interrupt task OB30 to show the disadvantages of "
        "such programs. The push-button TL is wired as a normally open (NO) contact; LED is a digital output.\n"
        "Task: the program of Fig. 4.176, 'TL -> S LED' (if TL is pressed, SET the LED), runs in OB30 with a "
        "period of 1 s; its execution is very short (about 1 ms). OB30 is called at the STOP->RUN instant "
        "(0 s), then at 1 s, 2 s ... Enter the program in OB30 and analyse how the LED depends on the button: "
        "when does it light for a press from 0 s, for a press from 0.1 s, and for a short press between two "
        "calls?"
    ),
    io=OB30_IO,
    rig=ob30_panel,
    cpu=OB30_CPU,
    scenarios=[
        Scenario(
            FROM_0,
            *press("TL", t="0s", hold="1.5s..2.5s"),
            duration="3s",
            description="case (a): TL pressed at STOP->RUN (0 s) and held 1.5..2.5 s",
        ),
        Scenario(
            AFTER_0,
            *press("TL", t="50ms..950ms", hold="1.1s..2s"),
            duration="3s",
            description="case (b): TL pressed just after the 0 s call (0.05..0.95 s), held past the 1 s call",
        ),
        Scenario(
            SHORT,
            *press("TL", t="50ms..300ms", hold="100ms..500ms"),
            *press("TL", t="1.05s..1.3s", hold="100ms..600ms"),
            *press("TL", t="2.05s..2.3s", hold="100ms..600ms"),
            *press("TL", t="3.05s..3.5s", hold="1.2s..1.4s"),
            duration="5.5s",
            description="three presses that start and end between two calls, then one held over the 4 s call",
        ),
    ],
    checks=[
        only(eventually("LED").before("1ms").named("pressed from 0 s: the LED is set by the call at 0 s"), FROM_0),
        only(
            never("LED")
            .during("0s", "1s")
            .named("pressed after the 0 s call: the LED stays off until the call at 1 s"),
            AFTER_0,
        ),
        only(
            eventually(rises("LED"))
            .before("1s + 2ms")
            .named("pressed after the 0 s call: the LED is set by the call at 1 s"),
            AFTER_0,
        ),
        only(never("LED").during("0s", "4s").named("a press between two calls is never seen"), SHORT),
        only(
            eventually(rises("LED")).before("4s + 2ms").named("a press held over a call is seen by that call (4 s)"),
            SHORT,
        ),
        never(falls("LED")).named("once set, the LED stays lit"),
    ],
    requirements={
        "pressed from 0 s: the LED is set by the call at 0 s": IN_OB30,
        "pressed after the 0 s call: the LED stays off until the call at 1 s": IN_OB30,
        "pressed after the 0 s call: the LED is set by the call at 1 s": IN_OB30,
        "a press between two calls is never seen": IN_OB30,
        "a press held over a call is seen by that call (4 s)": IN_OB30,
        "once set, the LED stays lit": IN_OB30,
    },
    solutions=[
        solution(NUMBER, "reference", explanation="TL -> S LED in OB30 (1 s)"),
        solution(
            NUMBER,
            "wrong-in-ob1",
            "wrong",
            "the network in OB1: the LED comes within a scan and short presses are seen too",
            fails=(
                "pressed after the 0 s call: the LED stays off until the call at 1 s",
                "a press between two calls is never seen",
            ),
        ),
    ],
    notes=(
        "OB30 calls come at 0 s, 1 s, 2 s ... and last 1 ms; the LED written by the call at T reaches the output "
        "module at T + 1 ms (it rises at 1.001 s for the call at 1 s). 'Stays off until the call at T' looks at "
        "every scan that starts before T (the OB1 scan ending at T ends before the call due then). The seeded "
        "press times are drawn inside one OB30 interval, so the call that first sees the button is known: the "
        "checks are the textbook's analysis (the LED rises at the first call at which TL is TRUE). The textbook "
        "shows no wrong program; 'wrong-in-ob1' is the contrast the exercise draws with the program cycle."
    ),
)
