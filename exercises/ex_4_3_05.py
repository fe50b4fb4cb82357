"""4.3.5 Conveyor control 1 (one object). Plant: CONV1.

Mutation testing (``plcsim mutate 4.3.5``): the mutant with the two networks swapped (SET after
RESET, so SET wins when S1 and S2 are both covered) is a correct program by the task's words: the
operator loads one object at a time ("Only one object is on the conveyor at a time"), so S1 and S2
never see an object at once, and the task says nothing of what the belt should do then. No scenario
loads a second object while the first waits at S2 (the spec's "RESET is later in the scan: wins if
both covered" is a remark on the reference, not a requirement of the task); the swapped order ships
as the alternative ``solution-reset-first``.
"""

from exercises._common import solution
from exercises._conveyor import CARRY, CONV1_IO, carries_objects, shuttle
from plants import Conv1
from plcsim.check import always, assumes, event, implies, never, off, parts_at_once, rises
from plcsim.exercise import Exercise, only
from plcsim.scenario import Scenario, place, remove

NUMBER = "4.3.5"


EXERCISE = Exercise(
    number=NUMBER,
    slug="conveyor-1",
    title="Conveyor control 1 (one object)",
    title_sk="Príklad 5 – Ovládanie dopravníka 1",
    task=(
        "A conveyor has sensor S1 at its beginning and S2 at its end, both wired as normally open contacts; they "
        "detect the objects it carries. The belt runs forward only (from S1 to S2), driven by output D1 "
        "(conveyor forward).\n"
        "Task: an object loaded at the beginning is detected by S1. " + CARRY + "; the belt runs only to carry an "
        "object loaded at S1. Only one object is on the conveyor at a time."
    ),
    io=CONV1_IO,
    rig=Conv1,
    scenarios=[
        Scenario(
            "three objects",
            *shuttle(3),
            duration="25s",
            description="load at S1, remove at S2 after 1 s, load the next one; three times",
        ),
        Scenario(
            "placed mid-belt",
            place("p1", at="belt", offset_mm=150.0, t="0.5s", noise=False),
            duration="4s",
            description="an object put between S1 and S2 on the idle belt: nothing happens",
        ),
        Scenario(
            "placed at S2",
            place("p1", at="S2", t="0.5s"),
            remove("p1", t="2s"),
            duration="4s",
            description="an object put straight at S2 on the idle belt: the belt stays off",
        ),
    ],
    checks=[
        only(
            rises("D1")
            .within("1 scan")
            .after(rises("S1"), provided=off("S2"))
            .named("D1 starts when S1 sees an object"),
            "three objects",
        ),
        *(only(check, "three objects") for check in carries_objects(3)),
        only(
            always(implies("S2", off("D1"))).named("the belt never runs while S2 sees an object"),
            "three objects",
            "placed at S2",
        ),
        never(event("part fell off")).named("no object falls off the belt"),
        only(never("D1").named("the belt stays off without a new object at S1"), "placed mid-belt", "placed at S2"),
    ],
    solutions=[
        solution(NUMBER, "reference", explanation="S1 -> SET D1, S2 -> RESET D1"),
        solution(
            NUMBER,
            "solution-reset-first",
            "alternative",
            "S2 -> RESET D1 written before S1 -> SET D1: the same belt, since one object at a time never covers "
            "S1 and S2 at once",
        ),
        solution(
            NUMBER,
            "wrong-coil",
            "wrong",
            "D1 follows S1 as a coil: the belt stops as soon as the object leaves S1",
            fails=("D1 stops when the object reaches S2", "transport S1 -> S2 takes 4.8 s +-10 %"),
        ),
    ],
    conditions=[assumes("Only one object is on the conveyor at a time", parts_at_once(1))],
    requirements={
        "D1 starts when S1 sees an object": "start the belt in the scan in which S1 detects the object",
        "the belt never runs while S2 sees an object": "so that the object stays on the belt at S2",
        "no object falls off the belt": "so that the object stays on the belt at S2",
        "the belt stays off without a new object at S1": "the belt runs only to carry an object loaded at S1",
    },
    spec_equivalent={
        "OB1: networks start_belt and stop_belt swapped": (
            "SET after RESET differs only while S1 and S2 both see an object, which the task rules out: 'Only one "
            "object is on the conveyor at a time'"
        ),
    },
)
