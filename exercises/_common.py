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
    *,
    suffix: str = ".py",
) -> Solution:
    """A shipped program: ``exercises/solutions/4_3_NN/<name>.py`` (``T_NN/<name>.il`` for ``T-NN``)."""
    if "." in number:
        major, minor, item = number.split(".")
        folder = f"{major}_{minor}_{int(item):02d}"
    else:
        folder = number.replace("-", "_")
    return Solution(name, SOLUTIONS / folder / f"{name}{suffix}", kind, explanation, fails, scenarios)
