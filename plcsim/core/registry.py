"""Where plcsim finds what lives outside it: entry points of the installed packages (as gymnasium's
``register`` finds environments), so that ``plcsim/`` imports nothing from ``plants/`` or ``exercises/``
and an instructor's package adds exercises or rigs without editing this one.

Groups (``[project.entry-points."plcsim.rigs"]`` in a package's ``pyproject.toml``):

* ``plcsim.exercises``: a package of exercise modules (each module whose name does not start with ``_``
  defines ``EXERCISE``), one such module, or an :class:`~plcsim.exercise.model.Exercise` object;
  ``course = "exercises"`` registers the course's.
* ``plcsim.rigs``: a rig's id and its factory, ``CONV1 = "plants.conveyors:Conv1"``.
* ``plcsim.frontends``: a front end of another package, named by the file suffix it reads (``st =
  "my_st:read_st"`` reads ``.st``; a :class:`plcsim.frontends.FrontEnd` names its profile too);
  plcsim's own front ends register in :mod:`plcsim.frontends`.
* ``plcsim.profiles``: a CPU profile (:class:`plcsim.controllers.profiles.Profile`) by name, ``s7-1200 =
  "plcsim.controllers.s7.profile:PROFILE"`` (:mod:`plcsim.controllers.profiles` reads them).

A module is imported only when what it registers is asked for (``plcsim --help`` lists the rigs from the
names alone). A file in the working folder never stands in for a registered module: a student's
``exercises.py`` beside their program does not replace the course (:func:`installed_only`).
"""

from __future__ import annotations

import importlib.metadata
import os
import sys
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import Any

from plcsim.core.errors import ConfigurationError, did_you_mean

EXERCISES = "plcsim.exercises"
RIGS = "plcsim.rigs"
FRONTENDS = "plcsim.frontends"
PROFILES = "plcsim.profiles"


def entry_points(group: str) -> list[importlib.metadata.EntryPoint]:
    """The entry points of ``group`` in every installed distribution, in a stable order (by name)."""
    found = {ep.name: ep for ep in importlib.metadata.entry_points(group=group)}
    return [found[name] for name in sorted(found)]


def load(ep: importlib.metadata.EntryPoint) -> Any:
    """What an entry point names, imported from its installed package, never from the working folder."""
    with installed_only():
        try:
            return ep.load()
        except ConfigurationError:
            raise
        except Exception as exc:  # a broken plug-in is named, not a traceback
            raise ConfigurationError(
                f"the {ep.group} entry point {ep.name} = {ep.value!r} cannot be loaded: {type(exc).__name__}: {exc}"
            ) from exc


@contextmanager
def installed_only() -> Iterator[None]:
    """While plug-ins load (and the modules they import), the working folder is not searched: it is on
    ``sys.path`` in a notebook, ``python -c`` or ``python -m``, and a student's ``plants.py`` there would
    stand in for the rigs. Entries added meanwhile (an instructor's folder) stay."""
    here = _working_folder_entries()
    if not here:
        yield
        return
    saved = list(sys.path)
    sys.path[:] = [p for p in saved if p not in here]
    try:
        yield
    finally:
        sys.path[:] = saved + [p for p in sys.path if p not in saved]


def rig_names() -> list[str]:
    """The ids of the registered rigs (``PANEL``, ``CONV1`` ...), without importing them."""
    return [ep.name for ep in entry_points(RIGS)]


def rig(name: str) -> Callable[..., Any]:
    """The factory of the rig ``name`` (any case): ``rig("conv1")(end="stop")`` builds one."""
    for ep in entry_points(RIGS):
        if ep.name.upper() == name.upper():
            return load(ep)
    names = rig_names()
    raise ConfigurationError(f"no rig {name!r}{did_you_mean(name, names)} (rigs: {', '.join(names) or 'none'})")


def is_rig(name: str) -> bool:
    """True if ``name`` is a registered rig's id (any case)."""
    return name.upper() in {n.upper() for n in rig_names()}


def frontend(suffix: str) -> Callable[[Path], Any] | None:
    """The reader another package registered for files ending in ``suffix`` (``".st"``), or None."""
    name = suffix.lower().removeprefix(".")
    for ep in entry_points(FRONTENDS):
        if ep.name.lower() == name:
            return load(ep)
    return None


def frontend_suffixes() -> list[str]:
    """The suffixes other packages registered front ends for (``[".st"]``)."""
    return [f".{ep.name.lower()}" for ep in entry_points(FRONTENDS)]


# -- a file in the working folder does not stand in for an installed module ---------------------------


def _working_folder_entries() -> set[str]:
    cwd = os.getcwd()
    return {p for p in sys.path if p in ("", ".") or _same_folder(p, cwd)}


def _same_folder(a: str, b: str) -> bool:
    try:
        return Path(a).resolve() == Path(b).resolve()
    except OSError:
        return False


__all__ = [
    "EXERCISES",
    "FRONTENDS",
    "PROFILES",
    "RIGS",
    "entry_points",
    "frontend",
    "frontend_suffixes",
    "installed_only",
    "is_rig",
    "load",
    "rig",
    "rig_names",
]
