"""Grading one program on one seed for the 20-seed tests (tests/course/test_seeds.py, tests/course/test_corpus.py).

A correct program is graded on every scenario it is meant for; a wrong one only on the scenarios
where the checks that explain its flaw apply (a static check needs one scenario), one at a time
until each of those checks has failed: that is all the claim "it fails on this seed, on that check"
needs, and it spares most of the runs of the wrong ones.
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path

from plcsim.check import StaticCheck
from plcsim.exercise.model import Exercise
from plcsim.grading.grader import grade
from plcsim.grading.report import Report

SEEDS = range(1, 21)


def scenarios_explaining(exercise: Exercise, fails: Sequence[str], allowed: Sequence[str] | None) -> list[str]:
    """The scenarios (in the exercise's order) where the named checks are graded."""
    names = [s.name for s in exercise.scenarios if allowed is None or s.name in allowed]
    wanted: set[str] = set()
    for gc in exercise.checks:
        if gc.name not in fails:
            continue
        if isinstance(gc.check, StaticCheck):
            wanted.add(names[0])
        else:
            wanted.update(n for n in names if gc.scenarios is None or n in gc.scenarios)
    unknown = set(fails) - {gc.name for gc in exercise.checks}
    assert not unknown, f"{exercise.number}: no check named {sorted(unknown)}"
    return [n for n in names if n in wanted]


def failures(report: Report) -> str:
    """The failed checks of a report, one a line, for an assertion message."""
    lines = [f"{c.scenario}: {c.check}: {c.message}" for c in report.failed()]
    return "\n".join(lines + ([f"error: {report.error}"] if report.error else []))


def assert_passes(exercise: Exercise, path: Path, seed: int, scenarios: Sequence[str] | None = None) -> None:
    """A correct program: every check of every scenario passes on this seed."""
    report = grade(exercise, path, seed=seed, scenarios=scenarios)
    assert report.error is None, report.error
    assert report.passed and report.score == report.max_score > 0, f"seed {seed}:\n{failures(report)}"


def assert_fails(
    exercise: Exercise, path: Path, seed: int, fails: Sequence[str], scenarios: Sequence[str] | None = None
) -> None:
    """A wrong program: every check named in ``fails`` fails on this seed.

    The scenarios are graded one at a time and the grading stops as soon as every named check has
    failed in one of them: that is all the claim needs, and it spares the rest of the runs.
    """
    assert fails, f"{path.name} is wrong but names no check that exposes it"
    failed: set[str] = set()
    for scenario in scenarios_explaining(exercise, fails, scenarios):
        report = grade(exercise, path, seed=seed, scenarios=[scenario])
        assert report.error is None, report.error
        failed |= {c.check for c in report.failed()}
        if failed >= set(fails):
            return
    missing = sorted(set(fails) - failed)
    assert not missing, f"seed {seed}: should fail {missing}; it failed {sorted(failed)}"
