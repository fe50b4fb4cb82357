"""The old dotted paths of plcsim 0.1, kept importing for one release with a DeprecationWarning.

plcsim 0.1 kept about fifty modules side by side in ``plcsim/``; they now live in packages named after
their jobs (``docs/architecture.md``). An instructor's exercise file or a notebook that imports an old
path (``from plcsim.cpu import CPU``, ``import plcsim.tecomat.cpu``) still works and is told where the
module went. An old module that became one module gets that very module (monkeypatching it patches the
real one); one that was split gets a module that finds each name in the modules it was split into.

The public paths (``plcsim.check``, ``plcsim.scenario``, ``plcsim.exercise``, ``plcsim.plant``,
``plcsim.trace``, ``plcsim.grading``, ``plcsim.sim``, ``plcsim.tags``, ``plcsim.mutate`` and the names of
``plcsim`` itself) are packages now and are not aliases: they import without a warning.
"""

from __future__ import annotations

import importlib
import importlib.abc
import importlib.util
import sys
import types
import warnings
from collections.abc import Sequence
from typing import Any

MODULES: dict[str, tuple[str, ...]] = {
    "plcsim.errors": ("plcsim.core.errors",),
    "plcsim.clock": ("plcsim.core.clock",),
    "plcsim.literals": ("plcsim.core.literals",),
    "plcsim.observers": ("plcsim.core.observers",),
    "plcsim.registry": ("plcsim.core.registry",),
    "plcsim.safe_output": ("plcsim.core.safe_output",),
    "plcsim.types": ("plcsim.tags.types",),
    "plcsim.memory": ("plcsim.tags.memory",),
    "plcsim.trace_table": ("plcsim.trace.table",),
    "plcsim.trace_rows": ("plcsim.trace.rows",),
    "plcsim.trace_plot": ("plcsim.trace.plot",),
    "plcsim.trace_rerun": ("plcsim.trace.rerun",),
    "plcsim.actions": ("plcsim.scenario.runner",),
    "plcsim.controller": ("plcsim.controllers.protocol", "plcsim.controllers.choice", "plcsim.frontends.il"),
    "plcsim.loaded": ("plcsim.controllers.loaded",),
    "plcsim.cpu": ("plcsim.controllers.s7.cpu",),
    "plcsim.execution": ("plcsim.controllers.s7.execution",),
    "plcsim.access": ("plcsim.controllers.s7.access",),
    "plcsim.config": ("plcsim.controllers.s7.config", "plcsim.controllers.protocol"),
    "plcsim.program": (
        "plcsim.frontends.python.names",
        "plcsim.frontends.python.program",
        "plcsim.frontends.python.pipeline",
        "plcsim.frontends.python.link",
        "plcsim.controllers.s7.instructions",
    ),
    "plcsim.compiler": (
        "plcsim.frontends.python.rewrite",
        "plcsim.frontends.python.subset",
        "plcsim.frontends.python.merge",
        "plcsim.frontends.python.analysis",
        "plcsim.frontends.python.typecheck",
        "plcsim.frontends.python.safe_math",
    ),
    "plcsim.module_level": ("plcsim.frontends.python.module_level",),
    "plcsim.safe_math": ("plcsim.frontends.python.safe_math",),
    "plcsim.reference": ("plcsim.frontends.python.reference",),
    "plcsim.program_text": ("plcsim.frontends.text",),
    "plcsim.wiring": ("plcsim.sim.wiring",),
    "plcsim.recorder": ("plcsim.sim.recorder",),
    "plcsim.exercised": ("plcsim.check.exercised",),
    "plcsim.validation": ("plcsim.exercise.validation",),
    "plcsim.catalog": ("plcsim.exercise.catalog",),
    "plcsim.grade_report": ("plcsim.grading.report",),
    "plcsim.report": ("plcsim.grading.terminal",),
    "plcsim.run_result": ("plcsim.grading.run_result",),
    "plcsim.executors": ("plcsim.grading.executors",),
    "plcsim.sandbox": (
        "plcsim.grading.sandbox.parent",
        "plcsim.grading.sandbox.probes",
        "plcsim.grading.sandbox.readable",
        "plcsim.grading.sandbox.importable",
    ),
    "plcsim.sandbox_child": ("plcsim.grading.sandbox.child", "plcsim.grading.sandbox.exits"),
    "plcsim.forkserver": ("plcsim.grading.sandbox.forkserver",),
    "plcsim.confine": ("plcsim.grading.sandbox.confine",),
    "plcsim.watchdog": ("plcsim.grading.sandbox.watchdog",),
    "plcsim.mutate_il": ("plcsim.mutate.il",),
    "plcsim.cli": ("plcsim.apps.cli",),
    "plcsim.pytest_plugin": ("plcsim.apps.pytest_plugin",),
    "plcsim.profiles": ("plcsim.controllers.profiles",),
    "plcsim.profiles.listing": ("plcsim.apps.listing",),
    "plcsim.profiles.s7": ("plcsim.controllers.s7.profile", "plcsim.trace.table"),
    "plcsim.profiles.tecomat": ("plcsim.controllers.tecomat.profile",),
    "plcsim.tecomat.assembler": (
        "plcsim.controllers.tecomat.assembler",
        "plcsim.controllers.tecomat.assembly",
        "plcsim.controllers.tecomat.decoder",
    ),
    "plcsim.tecomat.instructions": ("plcsim.controllers.tecomat.instructions", "plcsim.controllers.tecomat.linker"),
}
"""An old module -> the module(s) its names are in now (several where it was split)."""

PACKAGES: dict[str, str] = {
    "plcsim.tecomat": "plcsim.controllers.tecomat",
    "plcsim.instructions": "plcsim.controllers.s7.instructions",
    "plcsim.live": "plcsim.apps.live",
}
"""An old package moved whole -> where it is: ``plcsim.tecomat.cpu`` is ``plcsim.controllers.tecomat.cpu``."""


def new_home(old: str) -> tuple[str, ...] | None:
    """Where the old module ``old`` lives now, or None if it did not move."""
    if old in MODULES:
        return MODULES[old]
    for package, home in PACKAGES.items():
        if old == package or old.startswith(package + "."):
            return (home + old[len(package) :],)
    return None


def _was_package(old: str) -> bool:
    """Whether ``old`` had submodules of its own that moved (``plcsim.profiles`` had ``.s7``)."""
    return any(name.startswith(old + ".") for name in MODULES)


class _Split(types.ModuleType):
    """An old module split into several, or an old package whose ``__init__`` became a module (it keeps
    a ``__path__`` so that its old submodules import): each name is looked up in the new modules."""

    def __init__(self, name: str, homes: Sequence[str]) -> None:
        super().__init__(name, f"Moved: its names are in {', '.join(homes)}.")
        self._homes = tuple(homes)
        if _was_package(name):
            self.__path__: list[str] = []

    def __getattr__(self, name: str) -> Any:
        for home in self._homes:
            module = importlib.import_module(home)
            if hasattr(module, name):
                return getattr(module, name)
        raise AttributeError(
            f"module {self.__name__!r} has no attribute {name!r} (it moved to {', '.join(self._homes)})"
        )


class _OldPaths(importlib.abc.MetaPathFinder, importlib.abc.Loader):
    """Finds an old dotted path and hands out the module that lives there now."""

    def find_spec(self, fullname: str, path: Any = None, target: Any = None) -> importlib.machinery.ModuleSpec | None:
        if not fullname.startswith("plcsim.") or new_home(fullname) is None:
            return None
        return importlib.util.spec_from_loader(fullname, self)

    def create_module(self, spec: importlib.machinery.ModuleSpec) -> types.ModuleType:
        return types.ModuleType(spec.name)

    def exec_module(self, module: types.ModuleType) -> None:
        homes = new_home(module.__name__)
        assert homes is not None
        warnings.warn(
            f"{module.__name__} moved to {' and '.join(homes)}; import it from there "
            f"(the old path is kept for one release)",
            DeprecationWarning,
            stacklevel=2,
        )
        # the import system hands out what sys.modules holds after this call: the real module
        name = module.__name__
        whole = len(homes) == 1 and not _was_package(name)
        sys.modules[name] = importlib.import_module(homes[0]) if whole else _Split(name, homes)


def install() -> None:
    """Make the old paths import (once per process; ``plcsim/__init__`` calls it)."""
    if not any(isinstance(finder, _OldPaths) for finder in sys.meta_path):
        sys.meta_path.insert(0, _OldPaths())
