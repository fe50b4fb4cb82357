"""What the CONV1 exercises (4.3.5, 4.3.7, 4.3.14 ...) share: the I/O table, the operator's shuttle
and the checks of plain conveyor control."""

from __future__ import annotations

from plcsim.check import Check, all_of, count, falls, never, off, rises
from plcsim.exercise import IO
from plcsim.scenario import after_event, held, place, remove

NOMINAL_TRANSPORT_S = 4.8
"""S1 -> S2 at 50 mm/s with the object placed centred on S1 (spec §5.2); the 10 s watchdog of 4.3.7
has a 2.1x margin."""

CONV1_IO = [
    IO("S1", "sensor at the belt start", "Bool", "%I0.0", "NO", comment="address proposed"),
    IO("S2", "sensor at the belt end", "Bool", "%I0.1", "NO", comment="address proposed"),
    IO("D1", "conveyor forward", "Bool", "%Q0.2", comment="address stated in 4.3.14"),
]


CARRY = (
    "Carry it to the end of the conveyor, where S2 detects it: start the belt in the scan in which S1 detects the "
    "object and stop it in the scan in which S2 detects it, so that the object stays on the belt at S2. After it has "
    "been removed, a new object can be loaded and carried"
)
"""4.3.5's words for carrying one object, which :func:`carries_objects` grades (4.3.7 and 4.3.8 state them too)."""


def shuttle(parts: int) -> list:
    """Load a part at S1; the operator takes it from S2 after 1 s and loads the next one 1..2 s later."""
    actions = [place("p1", at="S1", t="0.3s..0.8s")]
    for k in range(1, parts + 1):
        actions.append(remove(f"p{k}", when=held("S2", "1s")))
        if k < parts:
            actions.append(place(f"p{k + 1}", at="S1", when=after_event("part removed", f"p{k}"), delay="1s..2s"))
    return actions


def carries_objects(objects: int) -> list[Check]:
    """The belt stops at S2, carries each object in the nominal time and starts once per object."""
    return [
        falls("D1")
        .within("1 scan")
        .after(rises("S2"))
        .named("D1 stops when the object reaches S2")
        .grades("stop it in the scan in which S2 detects it"),
        rises("S2")
        .between(f"{NOMINAL_TRANSPORT_S * 0.9}s", f"{NOMINAL_TRANSPORT_S * 1.1}s")
        .after(rises("S1"))
        .named("transport S1 -> S2 takes 4.8 s +-10 %")
        .grades("Carry it to the end of the conveyor, where S2 detects it"),
        count(rises("D1"))
        .equals(objects)
        .named("the belt starts once per object")
        .grades("After it has been removed, a new object can be loaded and carried"),
    ]


def keeps_conveyor_control() -> list[Check]:
    """The conveyor of 4.3.14 and 4.3.15 (spec: "Conveyor of 4.3.5, driven by output D1"; the task: "Keep the
    conveyor control of 4.3.5 (S1 starts the belt, S2 stops it)"), as states, since an object may be loaded
    while the belt already runs: the belt is never off for more than a scan while S1 (and not S2) sees an
    object, nor on for more than a scan while S2 sees one."""
    return [
        never(all_of("S1", off("S2"), off("D1")))
        .for_more_than("1 scan")
        .named("S1 starts the belt")
        .grades("S1 starts the belt"),
        never(all_of("S2", "D1")).for_more_than("1 scan").named("S2 stops the belt").grades("S2 stops it"),
    ]
