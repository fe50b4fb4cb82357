"""The exercises plcsim can grade, found by textbook number (``4.3.6``), slug (``conveyor-2``) or path.

They come from the packages that register them (:mod:`plcsim.core.registry`, group ``plcsim.exercises``: the
course's ``exercises`` package, an instructor's own package) and from an instructor's file or folder named
by path (``plcsim grade my_course/runon.py student.py``, ``plcsim list --exercises my_course/``): each
module defines ``EXERCISE``.

A module that cannot be loaded (a syntax error, an exercise that fails its validation) does not hide
the others: it is left out of :func:`all_exercises`, listed by :func:`broken_exercises` with its file,
line and error, and named when it is asked for.
"""

from __future__ import annotations

import importlib
import importlib.util
import pkgutil
import re
import shlex
import sys
import traceback
from dataclasses import dataclass
from functools import cache
from pathlib import Path
from types import ModuleType

from plcsim.core import registry
from plcsim.core.errors import ConfigurationError, ExerciseError, did_you_mean
from plcsim.exercise.model import Exercise

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
        """The number its module name stands for (``ex_4_3_05`` -> ``4.3.5``, ``ex_t_01`` -> ``t-01``)."""
        parts = self.module.rpartition(".")[2].removeprefix("ex_").split("_")
        if not parts[0].isdigit():
            return "-".join(parts).lower()
        return ".".join(str(int(p)) if p.isdigit() else p for p in parts)

    def __str__(self) -> str:
        if _LOCATED.match(self.error):
            return self.error
        return f"{self.file}:{self.line or '?'}: {self.error}"


def load_package(package: str) -> tuple[list[Exercise], list[BrokenExercise]]:
    """Import every exercise module of ``package`` (each whose name does not start with ``_``): the
    exercises that load, and the modules that do not."""
    return _load_all(_package_modules(importlib.import_module(package)))


def _package_modules(package: ModuleType) -> list[tuple[str, str]]:
    return [
        (f"{package.__name__}.{info.name}", str(Path(info.module_finder.path) / f"{info.name}.py"))  # type: ignore[union-attr]
        for info in sorted(pkgutil.iter_modules(package.__path__), key=lambda i: i.name)
        if not info.name.startswith("_") and not info.ispkg
    ]


def load_path(path: str | Path) -> tuple[list[Exercise], list[BrokenExercise]]:
    """The exercises of an instructor's file (``runon.py``) or folder (each of its modules whose name does
    not start with ``_``; helpers go in ``_name.py``), found by path, outside this package.

    The file's folder (for a package, the folder above it) is put on ``sys.path`` so that its helpers
    import and a grading child finds the module by name. A module name that is already taken by
    another module (``exercises``, ``plants``, ``numpy`` ...) is refused: rename the file.
    """
    path = Path(path).expanduser().resolve()
    if not path.exists():
        raise ConfigurationError(f"no exercise file or folder {path}")
    if path.is_file() and path.suffix != ".py":
        raise ConfigurationError(f"{path}: an exercise is a Python file (my_exercise.py) defining EXERCISE")
    package = path if path.is_dir() and (path / "__init__.py").is_file() else None
    if path.is_file():
        files = [path]
    else:
        files = sorted(p for p in path.glob("*.py") if not p.name.startswith("_"))
        if not files:
            raise ConfigurationError(f"{path}: no exercise files (*.py not starting with _) in this folder")
    prefix = f"{package.name}." if package else ""
    modules = [(prefix + f.stem, str(f)) for f in files]
    for name, file in [(package.name, str(package / "__init__.py"))] if package else modules:
        _refuse_shadowing(name, Path(file))
    root = (package.parent if package else files[0].parent).as_posix()
    if root not in sys.path:
        sys.path.append(root)  # last: a file of the course never shadows an installed module
    return _load_all(modules)


def _refuse_shadowing(name: str, file: Path) -> None:
    """Refuse a module name that another module (loaded or installed) already answers to."""
    loaded = sys.modules.get(name)
    if loaded is not None:
        where = getattr(loaded, "__file__", None)
    else:
        try:
            spec = importlib.util.find_spec(name)
        except (ImportError, ValueError):
            spec = None
        where = spec.origin if spec is not None else None
        if spec is None:
            return
    if where is None or Path(where).resolve() != file:
        raise ConfigurationError(
            f"{file}: the module name {name!r} is already taken by {where or 'a built-in module'}; rename the file"
        )


def _load_all(
    modules: list[tuple[str, str]], objects: list[Exercise] | None = None
) -> tuple[list[Exercise], list[BrokenExercise]]:
    """Import each ``(module, file)`` (and take the exercises registered as objects): the exercises that
    load, and the modules that do not."""
    loaded: list[Exercise] = []
    owner: dict[str, str] = {}  # number or slug -> the file that defines it
    broken: list[BrokenExercise] = []
    found: list[tuple[str, str, Exercise]] = []
    for name, file in modules:
        try:
            found.append((name, file, _load_module(name)))
        except Exception as exc:  # noqa: BLE001 - any error of one module is reported, the others load
            broken.append(_broken(name, file, exc))
    found += [(e.defined_at.rpartition(":")[0], e.defined_at.rpartition(":")[0], e) for e in objects or ()]
    for name, file, exercise in found:
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


def is_path(name: str) -> bool:
    """True if ``name`` names an exercise file or folder rather than a number or slug.

    >>> is_path("4.3.6"), is_path("conveyor-2"), is_path("my_course/runon.py"), is_path("runon.py")
    (False, False, True, True)
    """
    return name.endswith(".py") or "/" in name or "\\" in name or Path(name).is_dir()


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


def _order(number: str) -> tuple[int, tuple[int, ...], str]:
    """Textbook numbers in their order (4.3.2 before 4.3.10), then the other ids (``T-01``) by name."""
    parts = number.split(".")
    if not parts[0].isdigit():
        return (1, (), number)
    return (0, tuple(int(p) if p.isdigit() else 0 for p in parts), "")


@cache
def _catalog() -> tuple[tuple[Exercise, ...], tuple[BrokenExercise, ...]]:
    """Every registered exercise (group ``plcsim.exercises``), loaded once per process."""
    with registry.installed_only():
        return _load_registered()


def _load_registered() -> tuple[tuple[Exercise, ...], tuple[BrokenExercise, ...]]:
    modules: list[tuple[str, str]] = []
    objects: list[Exercise] = []
    broken: list[BrokenExercise] = []
    for ep in registry.entry_points(registry.EXERCISES):
        try:
            found = registry.load(ep)
        except ConfigurationError as exc:
            broken.append(BrokenExercise(ep.module, ep.value, None, str(exc)))
            continue
        if isinstance(found, Exercise):
            objects.append(found)
        elif isinstance(found, ModuleType) and hasattr(found, "__path__"):
            modules += _package_modules(found)
        elif isinstance(found, ModuleType):
            modules.append((found.__name__, str(getattr(found, "__file__", found.__name__))))
        else:
            why = f"names a {type(found).__name__}, not an exercise package, module or Exercise"
            broken.append(BrokenExercise(ep.module, ep.value, None, f"the entry point {ep.name} = {ep.value!r} {why}"))
    exercises, unloaded = _load_all(modules, objects)
    return tuple(exercises), tuple(broken + unloaded)


def all_exercises() -> tuple[Exercise, ...]:
    """Every exercise that loads, in textbook order."""
    return _catalog()[0]


def broken_exercises() -> tuple[BrokenExercise, ...]:
    """The exercise modules that could not be loaded, with their file, line and error."""
    return _catalog()[1]


def get(name: str) -> Exercise:
    """An exercise by number (``4.3.6``, ``T-01`` in any case), slug (``conveyor-2``) or the path of an exercise file.

    Raises:
        ExerciseError: the exercise's module is broken (its file, line and error are named).
        ConfigurationError: there is no such exercise.
    """
    if is_path(name):
        return _by_path(name)
    key = name.strip().lower()
    for exercise in all_exercises():
        if key in (exercise.number.lower(), exercise.slug):
            return exercise
    for bad in broken_exercises():
        if key == bad.number:
            raise ExerciseError(f"exercise {name} cannot be loaded: {bad}")
    choices = [e.number for e in all_exercises()] + [e.slug for e in all_exercises()]
    unloaded = "".join(f"\n(not loaded: {bad})" for bad in broken_exercises())
    raise ConfigurationError(
        f"no exercise {name!r}{did_you_mean(name, choices)}; `plcsim list` shows them all{unloaded}"
    )


def command_name(exercise: Exercise) -> str:
    """How a command names ``exercise`` so that it is found again: its number if it is registered, else its file
    (relative to the working directory when it lies below it), quoted for a shell. A hint such as "grade it with
    plcsim grade ..." repeats it: the number of an exercise loaded from a file finds nothing."""
    if any(e is exercise for e in all_exercises()):
        return exercise.number
    file = Path(exercise.defined_at.rpartition(":")[0]).resolve()
    if file.is_relative_to(Path.cwd()):
        file = file.relative_to(Path.cwd())
    return shlex.quote(file.as_posix())


def _by_path(name: str) -> Exercise:
    exercises, broken = load_path(name)
    if broken:
        raise ExerciseError(f"the exercise {name} cannot be loaded: {broken[0]}")
    if len(exercises) != 1:
        numbers = ", ".join(f"{e.number} ({e.defined_at.rpartition(':')[0]})" for e in exercises)
        raise ConfigurationError(f"{name} holds {len(exercises)} exercises ({numbers}); name the file of one")
    return exercises[0]


__all__ = [
    "BrokenExercise",
    "all_exercises",
    "broken_exercises",
    "command_name",
    "get",
    "is_path",
    "load_package",
    "load_path",
]
