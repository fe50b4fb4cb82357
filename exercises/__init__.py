"""The course's exercises, found by textbook number (``4.3.6``) or slug (``conveyor-2``).

Each module ``exercises/ex_4_3_NN.py`` defines ``EXERCISE``; its programs (the reference solution,
the textbook's alternatives and its deliberately wrong solutions) are PLC-subset files under
``exercises/solutions/4_3_NN/``.
"""

from __future__ import annotations

import importlib
import pkgutil
from functools import cache

from plcsim.errors import ConfigurationError, did_you_mean
from plcsim.exercise import Exercise


@cache
def all_exercises() -> tuple[Exercise, ...]:
    """Every exercise, in textbook order."""
    found = []
    for info in pkgutil.iter_modules(__path__):
        if info.name.startswith("ex_"):
            module = importlib.import_module(f"{__name__}.{info.name}")
            found.append(module.EXERCISE)
    return tuple(sorted(found, key=lambda e: tuple(int(p) for p in e.number.split("."))))


def get(name: str) -> Exercise:
    """An exercise by number (``4.3.6``) or slug (``conveyor-2``)."""
    key = name.strip().lower()
    for exercise in all_exercises():
        if key in (exercise.number, exercise.slug):
            return exercise
    choices = [e.number for e in all_exercises()] + [e.slug for e in all_exercises()]
    raise ConfigurationError(f"no exercise {name!r}{did_you_mean(name, choices)}; `plcsim list` shows them all")


__all__ = ["all_exercises", "get"]
