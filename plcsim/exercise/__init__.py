"""Exercises: task, I/O table, rig, scenarios, checks and solutions; their validation and the catalogue."""

from plcsim.exercise.model import (
    IO,
    Exercise,
    GradedCheck,
    Solution,
    only,
)

__all__ = [
    "IO",
    "Solution",
    "GradedCheck",
    "only",
    "Exercise",
]
