"""The course's exercises, found by textbook number (``4.3.6``) or slug (``conveyor-2``).

Each module ``exercises/ex_4_3_NN.py`` defines ``EXERCISE``; its programs (the reference solution,
the textbook's alternatives and its deliberately wrong solutions) are PLC-subset files under
``exercises/solutions/4_3_NN/``.

A module that cannot be loaded (a syntax error, an exercise that fails its validation) does not hide
the others: it is left out of :func:`all_exercises`, listed by :func:`broken_exercises` with its file,
line and error, and named when it is asked for.
"""

from __future__ import annotations

import importlib
import pkgutil
import re
import traceback
from dataclasses import dataclass
from functools import cache
from pathlib import Path

from plcsim.errors import ConfigurationError, ExerciseError, did_you_mean
from plcsim.exercise import Exercise

_LOCATED = re.compile(r"^\S+:\d+: ")  # a message that starts with the file and line it is about


@dataclass(frozen=True)
class BrokenExercise:
    """An exercise module that could not be loaded: where, and why (one message, no traceback)."""

    module: str
    file: str
    line: int | None
    error: str

    @property
    def number(self) -> str:
        """The textbook number its module name stands for (``ex_4_3_05`` -> ``4.3.5``)."""
        parts = self.module.rpartition(".")[2].removeprefix("ex_").split("_")
        return ".".join(str(int(p)) if p.isdigit() else p for p in parts)

    def __str__(self) -> str:
        if _LOCATED.match(self.error):
            return self.error
        return f"{self.file}:{self.line or '?'}: {self.error}"


def load_package(package: str) -> tuple[list[Exercise], list[BrokenExercise]]:
    """Import every ``ex_*`` module of ``package``: the exercises that load, and the modules that do not."""
    path = importlib.import_module(package).__path__
    loaded: list[Exercise] = []
    owner: dict[str, str] = {}  # number or slug -> the file that defines it
    broken: list[BrokenExercise] = []
    for info in sorted(pkgutil.iter_modules(path), key=lambda i: i.name):
        if not info.name.startswith("ex_"):
            continue
        name = f"{package}.{info.name}"
        file = str(Path(info.module_finder.path) / f"{info.name}.py")  # type: ignore[union-attr]
        try:
            exercise = _load_module(name)
        except Exception as exc:  # noqa: BLE001 - any error of one module is reported, the others load
            broken.append(_broken(name, file, exc))
            continue
        taken = [key for key in (exercise.number, exercise.slug) if key in owner]
        if taken:
            where = exercise.defined_at
            broken.append(
                BrokenExercise(name, file, None, f"{where}: {taken[0]!r} is already taken by {owner[taken[0]]}")
            )
            continue
        owner[exercise.number] = owner[exercise.slug] = file
        loaded.append(exercise)
    return sorted(loaded, key=lambda e: _order(e.number)), broken


def _load_module(name: str) -> Exercise:
    module = importlib.import_module(name)
    exercise = getattr(module, "EXERCISE", None)
    if not isinstance(exercise, Exercise):
        raise ExerciseError(f"{module.__file__}:1: the module defines no EXERCISE = Exercise(...)")
    return exercise


def _broken(module: str, file: str, exc: Exception) -> BrokenExercise:
    """Where the error is: a syntax error's own line, else the deepest line of the module's file."""
    if isinstance(exc, SyntaxError):
        return BrokenExercise(module, exc.filename or file, exc.lineno, f"SyntaxError: {exc.msg}")
    frames = [f for f in traceback.extract_tb(exc.__traceback__) if f.filename == file]
    line = frames[-1].lineno if frames else None
    kind = "" if isinstance(exc, ExerciseError) else f"{type(exc).__name__}: "
    return BrokenExercise(module, file, line, f"{kind}{exc}")


def _order(number: str) -> tuple[int, ...]:
    return tuple(int(p) if p.isdigit() else 0 for p in number.split("."))


@cache
def _catalog() -> tuple[tuple[Exercise, ...], tuple[BrokenExercise, ...]]:
    exercises, broken = load_package(__name__)
    return tuple(exercises), tuple(broken)


def all_exercises() -> tuple[Exercise, ...]:
    """Every exercise that loads, in textbook order."""
    return _catalog()[0]


def broken_exercises() -> tuple[BrokenExercise, ...]:
    """The exercise modules that could not be loaded, with their file, line and error."""
    return _catalog()[1]


def get(name: str) -> Exercise:
    """An exercise by number (``4.3.6``) or slug (``conveyor-2``).

    Raises:
        ExerciseError: the exercise's module is broken (its file, line and error are named).
        ConfigurationError: there is no such exercise.
    """
    key = name.strip().lower()
    for exercise in all_exercises():
        if key in (exercise.number, exercise.slug):
            return exercise
    for bad in broken_exercises():
        if key == bad.number:
            raise ExerciseError(f"exercise {name} cannot be loaded: {bad}")
    choices = [e.number for e in all_exercises()] + [e.slug for e in all_exercises()]
    unloaded = "".join(f"\n(not loaded: {bad})" for bad in broken_exercises())
    raise ConfigurationError(
        f"no exercise {name!r}{did_you_mean(name, choices)}; `plcsim list` shows them all{unloaded}"
    )


__all__ = ["BrokenExercise", "all_exercises", "broken_exercises", "get", "load_package"]
