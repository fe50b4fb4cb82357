"""SORT (plants/sort.py) and exercise 4.3.17: the rig's timing and ejection, and every shipped solution on seeds
1..20 (the reference passes; each wrong one fails on the check that explains its flaw)."""

from __future__ import annotations

import pytest

from exercises import get
from plants.sort import Sort
from plcsim.grading import grade

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
    for _ in range(1000):
        s.step(MS)
    assert [(e.subject, e.part, e.data) for e in s.events if e.kind == "part in bin"] == [("bin1", "p", {"colour": 1})]


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


EXERCISE = get("4.3.17")


@pytest.mark.parametrize("solution", EXERCISE.solutions, ids=[s.name for s in EXERCISE.solutions])
def test_every_solution_on_twenty_seeds(solution):
    for seed in range(1, 21):
        report = grade(EXERCISE, solution.path, seed=seed)
        assert report.error is None, report.error
        failed = {c.check for c in report.failed()}
        if solution.kind == "wrong":
            missing = set(solution.fails) - failed
            assert not missing, f"seed {seed}: {solution.name} should fail {sorted(missing)}; failed {sorted(failed)}"
        else:
            assert report.passed, f"seed {seed}: " + "; ".join(f"{c.scenario}: {c.message}" for c in report.failed())
