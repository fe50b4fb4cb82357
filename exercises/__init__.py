"""The course's exercises, found by textbook number (``4.3.6``) or slug (``conveyor-2``).

Each module ``exercises/ex_4_3_NN.py`` defines ``EXERCISE``; its programs (the reference solution,
the textbook's alternatives and its deliberately wrong solutions) are PLC-subset files under
``exercises/solutions/4_3_NN/``. The package is registered with plcsim in ``pyproject.toml``
(``[project.entry-points."plcsim.exercises"] course = "exercises"``); :mod:`plcsim.exercise.catalog` loads it,
and an instructor's own package or file beside it, the same way.

The names below are :mod:`plcsim.exercise.catalog`'s, kept here for notebooks and scripts that import them.
"""

from __future__ import annotations

from plcsim.exercise.catalog import (
    BrokenExercise,
    all_exercises,
    broken_exercises,
    get,
    is_path,
    load_package,
    load_path,
)

__all__ = ["BrokenExercise", "all_exercises", "broken_exercises", "get", "is_path", "load_package", "load_path"]
