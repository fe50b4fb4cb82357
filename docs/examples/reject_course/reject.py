"""REJECT: push the bad parts off the belt into the reject bin (an instructor's own exercise, on an own rig).

It lives outside the package: ``plcsim grade docs/examples/reject_course/reject.py alice.py`` finds it by path,
and ``plcsim check-exercise docs/examples/reject_course/reject.py --seeds 3`` checks that its reference passes and
each wrong solution fails where its ``fails=`` says.
"""

from __future__ import annotations

from pathlib import Path

from _reject_rig import Reject

from plcsim.check import all_of, durations, event_data, never, off, rises
from plcsim.exercise import IO, Exercise, Solution, only
from plcsim.scenario import Scenario, after_event, one_of, place

HERE = Path(__file__).parent
ONE_BAD, ONE_GOOD, THREE = "one bad part", "one good part", "three parts"
WITH_BAD, WITH_GOOD = (ONE_BAD, THREE), (ONE_GOOD, THREE)

SOLUTIONS = [
    Solution("reference", HERE / "solutions" / "reference.py", explanation="D1 latched at S1; Y1 a 0.4 s TP on B1"),
    Solution(
        "no-piston",
        HERE / "solutions" / "no_piston.py",
        "wrong",
        "runs the belt but never pushes: the bad parts ride into the good bin",
        fails=("Y1 pushes when B1 sees a bad part", "only good parts in the good bin"),
    ),
    Solution(
        "piston-follows-B1",
        HERE / "solutions" / "piston_follows_b1.py",
        "wrong",
        "Y1 := B1: the piston goes back as soon as the part has left the spot, before the stroke is done",
        fails=("Y1 stays out 0.4 s",),
    ),
]

EXERCISE = Exercise(
    number="9.7.1",
    slug="reject-bad-parts",
    title="Reject the bad parts",
    task=(
        "Parts are placed at the entry S1 of belt D1. D1 starts in the scan S1 sees a part and keeps running. "
        "The inspection sensor B1, in front of piston Y1, is TRUE while a bad part is in front of the piston: "
        "extend Y1 from the scan in which B1 sees a bad part for 0.4 s (±1 scan), so that it pushes the part into "
        "the reject bin. Good parts ride on into the good bin at the belt's end."
    ),
    io=[
        IO("S1", "light barrier at the entry", "Bool", "%I0.0", "NO"),
        IO("S2", "light barrier at the end", "Bool", "%I0.1", "NO"),
        IO("B1", "inspection: a bad part in front of the piston", "Bool", "%I0.2", "NO"),
        IO("D1", "belt forward", "Bool", "%Q0.0"),
        IO("Y1", "piston forward", "Bool", "%Q0.1"),
    ],
    rig=Reject,
    scenarios=[
        Scenario(ONE_BAD, place("p1", at="S1", t="0.3s..0.8s", bad=True), duration="6s"),
        Scenario(ONE_GOOD, place("p1", at="S1", t="0.3s..0.8s", bad=False), duration="8s"),
        Scenario(
            THREE,
            place("p1", at="S1", t="0.3s..0.8s", bad=True),
            place("p2", at="S1", when=after_event("part left", "S1"), delay="1.5s..2.5s", bad=False),
            place("p3", at="S1", when=after_event("part placed", "p2"), delay="2.5s..3.5s", bad=one_of(True, False)),
            duration="14s",
        ),
    ],
    checks=[
        never(all_of("S1", off("D1"))).named("the belt runs when a part is at S1"),
        only(rises("Y1").within("1 scan").after(rises("B1")).named("Y1 pushes when B1 sees a bad part"), *WITH_BAD),
        only(durations("Y1").between("0.4s - 1 scan", "0.4s + 1 scan").named("Y1 stays out 0.4 s"), *WITH_BAD),
        only(event_data("part in bin", "bad", "reject").equals(1).named("only bad parts in the reject bin"), *WITH_BAD),
        only(event_data("part in bin", "bad", "good").equals(0).named("only good parts in the good bin"), *WITH_GOOD),
    ],
    solutions=[s for s in SOLUTIONS if s.path.is_file()],
)
