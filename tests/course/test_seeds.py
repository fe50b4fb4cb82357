"""Every shipped solution graded on the seeds 1..20: each correct one (reference, alternative) passes
every check on every seed; each wrong one fails, on every seed, every check its ``fails`` names.

One test per exercise, solution and seed, so that a failure names all three. A wrong solution is
graded only on the scenarios where the checks that explain it apply, until they have failed
(tests/seeded.py); the rest is graded as ``plcsim grade`` grades it.
"""

from __future__ import annotations

import pytest
from seeded import SEEDS, assert_fails, assert_passes, scenarios_explaining

from exercises import all_exercises, get


def _cases() -> list:
    cases = []
    for ex in all_exercises():
        for sol in ex.solutions:
            for seed in SEEDS:
                cases.append(pytest.param(ex, sol, seed, id=f"{ex.number}-{sol.name}-{seed}"))
    return cases


@pytest.mark.parametrize(("exercise", "solution", "seed"), _cases())
def test_solution_grades_as_shipped_on_every_seed(exercise, solution, seed):
    if solution.kind in ("reference", "alternative"):
        assert_passes(exercise, solution.path, seed, solution.scenarios)
    else:
        assert_fails(exercise, solution.path, seed, solution.fails, solution.scenarios)


def test_the_seed_helpers_can_fail():
    ex = get("4.3.3")
    reference, coil = (next(s.path for s in ex.solutions if s.name == n) for n in ("reference", "wrong-coil"))
    with pytest.raises(AssertionError, match="once lit, the LED stays lit"):
        assert_passes(ex, coil, 1)
    with pytest.raises(AssertionError, match="should fail"):
        assert_fails(ex, reference, 1, ("once lit, the LED stays lit (until the CPU is stopped)",))
    with pytest.raises(AssertionError, match="no check named"):
        assert_fails(ex, coil, 1, ("the LED blinks",))
    assert scenarios_explaining(ex, ("no SET instruction",), None) == ["presses"]
    assert scenarios_explaining(ex, ("once lit, the LED stays lit (until the CPU is stopped)",), ("long wait",)) == [
        "long wait"
    ]
