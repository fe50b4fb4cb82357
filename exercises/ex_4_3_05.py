"""4.3.5 Conveyor control 1 (one object). Plant: CONV1."""

from exercises._common import solution
from plants import Conv1
from plcsim.check import always, count, event, falls, implies, never, off, rises
from plcsim.exercise import IO, Exercise, only
from plcsim.scenario import Scenario, after_event, held, place, remove

NUMBER = "4.3.5"

NOMINAL_TRANSPORT_S = 4.8  # spec §5.2: S1 -> S2 at 50 mm/s, object placed centred on S1


def shuttle(parts: int) -> list:
    """Load a part at S1; the operator takes it from S2 after 1 s and loads the next one 1..2 s later."""
    actions = [place("p1", at="S1", t="0.3s..0.8s")]
    for k in range(1, parts + 1):
        actions.append(remove(f"p{k}", when=held("S2", "1s")))
        if k < parts:
            actions.append(place(f"p{k + 1}", at="S1", when=after_event("part removed", f"p{k}"), delay="1s..2s"))
    return actions


EXERCISE = Exercise(
    number=NUMBER,
    slug="conveyor-1",
    title="Conveyor control 1 (one object)",
    title_sk="Príklad 5 – Ovládanie dopravníka 1",
    task=(
        "A conveyor has sensor S1 at its beginning and S2 at its end, both wired as normally open contacts; they "
        "detect the objects it carries. The belt runs forward only (from S1 to S2), driven by output D1 "
        "(conveyor forward).\n"
        "Task: an object loaded at the beginning is detected by S1. Carry it to the end of the conveyor, where S2 "
        "detects it. After it has been removed, a new object can be loaded and carried. Only one object is on the "
        "conveyor at a time."
    ),
    io=[
        IO("S1", "sensor at the belt start", "Bool", "%I0.0", "NO", comment="address proposed"),
        IO("S2", "sensor at the belt end", "Bool", "%I0.1", "NO", comment="address proposed"),
        IO("D1", "conveyor forward", "Bool", "%Q0.2", comment="address stated in 4.3.14"),
    ],
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
        only(
            falls("D1").within("1 scan").after(rises("S2")).named("D1 stops when the object reaches S2"),
            "three objects",
        ),
        only(
            rises("S2")
            .between(f"{NOMINAL_TRANSPORT_S * 0.9}s", f"{NOMINAL_TRANSPORT_S * 1.1}s")
            .after(rises("S1"))
            .named("transport S1 -> S2 takes 4.8 s +-10 %"),
            "three objects",
        ),
        only(count(rises("D1")).equals(3).named("the belt starts once per object"), "three objects"),
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
            "wrong-coil",
            "wrong",
            "D1 follows S1 as a coil: the belt stops as soon as the object leaves S1",
            fails=("D1 stops when the object reaches S2", "transport S1 -> S2 takes 4.8 s +-10 %"),
        ),
    ],
)
