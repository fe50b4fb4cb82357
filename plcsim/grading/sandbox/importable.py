"""How a fresh interpreter finds what this one has loaded: the module and attribute of an exercise,
and the top-level folder of a loaded module.

A grading child (:mod:`plcsim.grading.sandbox.child`) and a batch's worker elsewhere
(:class:`plcsim.grading.batch.ExerciseRef`) import the exercise by these names; the list of what the
child may read (:mod:`plcsim.grading.sandbox.readable`) grants the folders of the loaded packages.
"""

from __future__ import annotations

import functools
import sys
from pathlib import Path
from typing import Any

from plcsim.core.errors import ConfigurationError
from plcsim.exercise.model import Exercise


def locate(exercise: Exercise) -> tuple[str, str]:
    """The module and attribute a fresh interpreter finds ``exercise`` under (``EXERCISE`` first)."""
    modules = [(name, vars(m)) for name, m in list(sys.modules.items()) if name != "__main__" and m is not None]
    for name, namespace in modules:
        if namespace.get("EXERCISE") is exercise:
            return name, "EXERCISE"
    for name, namespace in modules:
        for attribute, value in list(namespace.items()):
            if value is exercise:
                return name, attribute
    raise ConfigurationError(
        f"exercise {exercise.number} is not importable by a module name, so a grading child cannot load it; "
        f"define it in a module (EXERCISE = Exercise(...)) or grade in this process with grade()"
    )


def package_root(module: Any) -> Path | None:
    """The top-level package folder (or the file) a loaded module comes from."""
    file = getattr(module, "__file__", None)
    return _root_of(file, module.__name__.count(".")) if file else None


@functools.lru_cache(maxsize=8192)
def _root_of(file: str, depth: int) -> Path:
    """The folder ``depth`` levels above a package module's file (its file, for a top-level module)."""
    top = Path(file).resolve().parent if Path(file).name == "__init__.py" else Path(file).resolve()
    for _ in range(depth):
        top = top.parent
    return top
