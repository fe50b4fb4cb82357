"""Every exercise's shipped solutions, graded: the reference (and the textbook's correct
alternatives) pass every check; each wrong solution fails on the check that explains its flaw.

The runs are the same as ``plcsim grade EXERCISE FILE`` in-process (the sandbox is tested in
tests/grading/test_grading.py), with the default seed and a second seed for the reference, so that a
solution cannot pass by chance of one timing.
"""

from __future__ import annotations

import pytest

from exercises import all_exercises
from plcsim.grading.grader import grade

CASES = [(ex, sol) for ex in all_exercises() for sol in ex.solutions]


@pytest.mark.parametrize(("exercise", "solution"), CASES, ids=[f"{e.number}-{s.name}" for e, s in CASES])
def test_solution_grades_as_the_textbook_says(exercise, solution):
    scenarios = solution.scenarios
    report = grade(exercise, solution.path, seed=1, scenarios=scenarios)
    assert report.error is None, report.error
    failed = {c.check for c in report.failed()}
    if solution.kind in ("reference", "alternative"):
        assert not failed, "\n".join(f"{c.scenario}: {c.check}: {c.message}" for c in report.failed())
        assert report.passed and report.score == report.max_score > 0
    else:
        assert solution.fails, f"{solution.name} is wrong but names no check that exposes it"
        missing = set(solution.fails) - failed
        assert not missing, (
            f"{solution.name} should fail {sorted(missing)}; it failed {sorted(failed)}; "
            f"the textbook's point: {solution.explanation}"
        )
        assert not report.passed


REFERENCES = [(ex, ex.reference) for ex in all_exercises()]


@pytest.mark.parametrize(("exercise", "solution"), REFERENCES, ids=[e.number for e, _ in REFERENCES])
def test_reference_passes_with_another_seed(exercise, solution):
    report = grade(exercise, solution.path, seed=7)
    assert report.passed, "\n".join(f"{c.scenario}: {c.check}: {c.message}" for c in report.failed())


def test_every_exercise_has_a_reference_and_unique_numbers():
    numbers = [e.number for e in all_exercises()]
    slugs = [e.slug for e in all_exercises()]
    assert len(set(numbers)) == len(numbers) and len(set(slugs)) == len(slugs)
    for ex in all_exercises():
        assert sum(s.kind == "reference" for s in ex.solutions) == 1, ex.number
        for s in ex.solutions:
            assert s.path.is_file(), s.path
