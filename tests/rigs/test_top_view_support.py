"""A part pushed off the top-view belt is tied to the table after the step in which it left the belt's area."""

from __future__ import annotations

from plants.sort import Sort

MS = 1_000_000


def test_a_part_pushed_off_the_belt_slides_to_a_stop_on_the_table():
    s = Sort()
    pid = s.place("OS1", colour=1)
    s.actuate("Kompresor", True)
    s.actuate("D1_VPRED", True)
    part = s.parts[pid]
    while part.body.position.x < 245.0:  # in front of piston 1
        s.step(MS)
    s.actuate("Piest1_Farba1", True)
    belt = s.belt.body
    on_belt, vx = [], []
    while pid in s.parts:  # until it has lain in its bin for 0.6 s and leaves the physics
        s.step(MS)
        on_belt.append(s._joints[pid][0].a is belt) if pid in s._joints else None
        vx.append(part.body.velocity.x)
        assert not s.space._add_later and not s.space._remove_later  # nothing left for pymunk to do later
    assert [e.subject for e in s.events if e.kind == "part in bin"] == ["bin1"]
    left = on_belt.index(False)
    assert on_belt[:left] == [True] * left and not any(on_belt[left:])  # rode on the belt, then tied to the table
    assert max(vx[:left]) > 40.0 and abs(vx[-1]) < 1.0  # rode at the belt's 50 mm/s; in the bin it lies still
