"""SORT (plants/sort.py) and exercise 4.3.17: the rig's timing and ejection.

Every shipped solution of 4.3.17 is graded on the seeds 1..20 by tests/test_seeds.py."""

from __future__ import annotations

from plants.sort import Sort

MS = 1_000_000


def run_until(s: Sort, sensor: str, value: bool, limit_ms: int = 20_000) -> int:
    for _ in range(limit_ms):
        if s.sensors[sensor] == value:
            return s.now_ns
        s.step(MS)
    raise AssertionError(f"{sensor} never became {value}")


def test_a_part_rides_to_the_detection_barrier_in_1_6_s_and_reads_its_colour():
    s = Sort()
    s.place("OS1", part="p", colour=3)
    s.actuate("D1_VPRED", True)
    t = run_until(s, "OS2_Detekcia", True)
    # §5.8: OS1 -> OS2 ≈ 1.6 s: (120 - 1 - 12.5 - 30) mm at 50 mm/s + the drive's 50 ms lag = 1.58 s
    assert 1575 * MS <= t <= 1585 * MS
    assert abs(s.sensors["FARBA"] - 21000) < 2500  # colour 3 (blue), σ 500


def test_a_piston_fired_as_the_part_leaves_its_barrier_pushes_it_into_its_bin():
    s = Sort()
    s.place("OS1", part="p", colour=1)
    s.actuate("D1_VPRED", True)
    run_until(s, "OS3_Farba1", True)
    run_until(s, "OS3_Farba1", False)  # "occupied and the sensor free": the part has just passed
    s.actuate("Kompresor", True)
    s.actuate("Piest1_Farba1", True)
    for _ in range(2000):
        s.step(MS)
    assert [(e.subject, e.part, e.data) for e in s.events if e.kind == "part in bin"] == [("bin1", "p", {"colour": 1})]
    # at rest in the bin it has left the physics, and is still drawn there
    assert "p" not in s.parts and [d.path for d in s.dynamic_drawables() if d.path == "parts/p"] == ["parts/p"]


def test_without_air_the_piston_stays_back_and_the_part_ends_unsorted():
    s = Sort()
    s.place("OS1", part="p", colour=1)
    s.actuate("D1_VPRED", True)
    run_until(s, "OS3_Farba1", True)
    run_until(s, "OS3_Farba1", False)
    s.actuate("Piest1_Farba1", True)  # the valve opens, the compressor is off
    for _ in range(7000):
        s.step(MS)
    assert [(e.subject, e.part) for e in s.events if e.kind == "part in bin"] == [("unsorted", "p")]
