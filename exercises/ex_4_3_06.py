"""4.3.6 Conveyor control 2 (any number of objects). Plant: CONV1.

Mutation testing (``plcsim mutate 4.3.6``): the one equivalent mutant is CTUD's ``PV 0 -> 1``. PV
only decides QU (CV >= PV), which neither the reference nor any check reads; CV, and with it POCET
and D1, is the same.
"""

from __future__ import annotations

from collections.abc import Iterable

from exercises._common import SOLUTIONS, solution
from exercises._conveyor import CONV1_IO
from exercises._truth import EdgeBalance, Parts, parts_equal
from plants import Conv1
from plcsim.check import all_of, always, count, event, falls, final, implies, never, off, rises
from plcsim.exercise import IO, Exercise, Solution, only
from plcsim.scenario import FAULTS, Scenario, after_event, chatter, held, place, remove

NUMBER = "4.3.6"
FAULT_WORDS = "A bouncing sensor makes extra edges, and the count takes each edge as it comes"
"""The task's words for its fault scenarios (``Scenario(outside=...)``)."""

# --------------------------------------------------------------------------------------------
# The exercise
# --------------------------------------------------------------------------------------------

ON_BELT = Parts("S1", "S2", label="objects that passed S1 but have not reached S2")
HOLDS = ("1s", "1.4s", "0.8s", "1.2s", "1.1s")  # how long the operator lets the objects wait at S2


def removals(holds: Iterable[str]) -> list:
    """The operator takes the object at S2 away once it has waited there, one action per object.

    Every action is armed whenever S2 is interrupted, so at each arrival the shortest hold still waiting fires;
    the holds must differ (two equal ones would fire together and the second find nothing at S2).
    """
    return [remove("S2", when=held("S2", h)) for h in holds]


def five_objects() -> list:
    """Three objects loaded in a row; a fourth while the belt waits with the first at S2; a fifth later."""
    return [
        place("p1", at="S1", t="0.3s..0.8s"),
        place("p2", at="S1", when=after_event("part left", "p1"), delay="0.8s..1.5s"),
        place("p3", at="S1", when=after_event("part left", "p2"), delay="0.8s..1.5s"),
        place("p4", at="S1", when=held("S2", "0.2s"), delay="0s..0.5s"),
        place("p5", at="S1", when=after_event("part removed", "p3"), delay="0.3s..1s"),
        *removals(HOLDS),
    ]


EXERCISE = Exercise(
    number=NUMBER,
    slug="conveyor-2",
    title="Conveyor control 2 (any number of objects)",
    title_sk="Príklad 6 – Ovládanie dopravníka 2",
    task=(
        "The conveyor of 4.3.5: sensor S1 at the beginning and S2 at the end, both wired as normally open "
        "contacts; output D1 (conveyor forward) drives the belt from S1 to S2.\n"
        "Task: objects loaded at the beginning (and detected by S1) are carried to the end of the conveyor; S2 "
        "switches the conveyor off. Any number of objects may be on the conveyor. S2 may stop the belt while "
        "another object is still in the middle, so after the object at the end has been removed the program must "
        "know whether objects are left between S1 and S2: count them. Keep the count in POCET (number of "
        "objects, Int), either as an up/down counter CTUD whose CV output is wired to POCET, or with ADD/SUB on "
        "the edges of S1 and S2. The belt starts in the scan in which S1 sees an object loaded on the empty belt, "
        "restarts in the scan in which the removal frees S2 while objects remain, and runs only while an object is "
        "on it, never while S2 sees one, so that no object falls off. A bouncing sensor makes extra edges, and the "
        "count takes each edge as it comes (the textbook shows what that does to POCET)."
    ),
    io=[
        *CONV1_IO,
        IO(
            "POCET",
            "number of objects between S1 and S2",
            "Int",
            None,
            comment="symbolic tag; textbook solution 2 (solution 1: the CTUD's CV)",
        ),
    ],
    rig=Conv1,
    scenarios=[
        Scenario(
            "five objects",
            *five_objects(),
            duration="25s",
            description="three objects loaded in a row; the first stops the belt at S2 with two in the middle; "
            "a fourth is loaded while the belt waits, a fifth after the third removal; each is taken from S2 "
            "after waiting 0.8..1.4 s",
        ),
        Scenario(
            "noisy S1",
            chatter("S1", t="0s"),
            place("p1", at="S1", t="0.3s..0.8s"),
            place("p2", at="S1", when=after_event("part left", "p1"), delay="1s..2s"),
            *removals(("1s", "1.2s")),
            outside={FAULTS: FAULT_WORDS},
            duration="16s",
            description="demonstration (textbook, not pass/fail): S1 bounces 3..5 times at every beam change, "
            "so each object is counted several times; the count never returns to 0 and the belt runs on "
            "after the last removal",
        ),
        Scenario(
            "noisy S2",
            chatter("S2", when=held("S2", "0.5s")),
            place("p1", at="S1", t="0.3s..0.8s"),
            place("p2", at="S1", when=after_event("part removed", "S2"), delay="1s..2s"),
            *removals(("1s",)),
            outside={FAULTS: FAULT_WORDS},
            duration="12s",
            description="demonstration (textbook, not pass/fail): S2 bounces while the operator takes the "
            "object away, the count drops below 0 and a newly loaded object does not start the belt",
        ),
    ],
    checks=[
        only(count(event("part entered", "S2")).equals(5).named("every loaded object arrives at S2"), "five objects"),
        only(always(implies("S2", off("D1"))).named("the belt never runs while S2 sees an object"), "five objects"),
        only(
            rises("D1")
            .within("1 scan")
            .after(rises("S1"), provided=all_of(off("S2"), ON_BELT == 1))
            .named("an object loaded on the empty belt starts it"),
            "five objects",
        ),
        only(
            rises("D1")
            .within("1 scan")
            .after(falls("S2"), provided=ON_BELT > 0)
            .named("after a removal the belt restarts while objects remain"),
            "five objects",
        ),
        only(
            never(all_of("D1", ON_BELT == 0)).named("the belt never runs with no object between S1 and S2"),
            "five objects",
        ),
        only(
            always(parts_equal("POCET", ON_BELT)).named("POCET equals the number of objects between S1 and S2"),
            "five objects",
        ),
        only(final("POCET").equals(0).named("POCET is 0 when the belt is empty"), "five objects"),
        only(
            always(parts_equal("POCET", EdgeBalance("S1", "S2"))).named(
                "POCET counts the S1 edges up and the S2 edges down"
            ),
            "noisy S1",
            "noisy S2",
        ),
        never(event("part fell off")).named("no object falls off the belt"),
    ],
    requirements={
        "every loaded object arrives at S2": (
            "objects loaded at the beginning (and detected by S1) are carried to the end of the conveyor"
        ),
        "the belt never runs while S2 sees an object": "never while S2 sees one",
        "an object loaded on the empty belt starts it": (
            "The belt starts in the scan in which S1 sees an object loaded on the empty belt"
        ),
        "after a removal the belt restarts while objects remain": (
            "restarts in the scan in which the removal frees S2 while objects remain"
        ),
        "the belt never runs with no object between S1 and S2": "runs only while an object is on it",
        "POCET equals the number of objects between S1 and S2": "Keep the count in POCET (number of objects, Int)",
        "POCET is 0 when the belt is empty": "Keep the count in POCET (number of objects, Int)",
        "POCET counts the S1 edges up and the S2 edges down": "the count takes each edge as it comes",
        "no object falls off the belt": "so that no object falls off",
    },
    solutions=[
        solution(NUMBER, "reference", explanation="CTUD: CU := S1, CD := S2, CV => POCET; D1 := NOT S2 AND CV > 0"),
        solution(
            NUMBER,
            "solution-2",
            "alternative",
            "ADD/SUB of POCET on the rising edges of S1 and S2; D1 := NOT S2 AND POCET > 0",
        ),
        solution(
            NUMBER,
            "wrong-no-edges",
            "wrong",
            "ADD/SUB without edges run in every scan a sensor is covered: POCET is not the number of objects",
            fails=("POCET equals the number of objects between S1 and S2",),
        ),
        Solution(
            "wrong-single-object",
            SOLUTIONS / "4_3_06" / "wrong-single-object.py",
            "wrong",
            "the one-object program of 4.3.5: after the first object is removed nothing knows that others "
            "wait in the middle, so the belt stays off",
            ("every loaded object arrives at S2", "after a removal the belt restarts while objects remain"),
        ),
    ],
    notes=(
        "Criterion 5 (noisy sensors) is a demonstration in the textbook, not pass/fail. It ships as the scenarios "
        "'noisy S1' and 'noisy S2', graded only on what stays true with noise (POCET follows the edges the PLC "
        "saw; nothing falls off); the count drifting away from the true number of objects is the thing to look "
        "at in the POCET plot. 'In loading order' (criterion 1) needs no check: parts on one belt cannot overtake. "
        "POCET is required by name so that both textbook solutions can be graded on their count (the CTUD "
        "solution wires its CV output to POCET)."
    ),
)
