"""Helpers shared by the exercise modules."""

from __future__ import annotations

from pathlib import Path

from plcsim.exercise import Solution

SOLUTIONS = Path(__file__).parent / "solutions"


def solution(
    number: str,
    name: str,
    kind: str = "reference",
    explanation: str = "",
    fails: tuple[str, ...] = (),
    scenarios: tuple[str, ...] | None = None,
) -> Solution:
    """A shipped program: ``exercises/solutions/4_3_NN/<name>.py``."""
    major, minor, item = number.split(".")
    path = SOLUTIONS / f"{major}_{minor}_{int(item):02d}" / f"{name}.py"
    return Solution(name, path, kind, explanation, fails, scenarios)
