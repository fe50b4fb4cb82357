"""What a grading child may read: a list of allowed files and folders, never of forbidden ones.

The child applies it to itself once the exercise is loaded (Landlock, :mod:`plcsim.grading.sandbox.confine`):
the submission, the Python installation, the folders of the packages the grader has loaded and the
system's libraries; not the exercise's solutions, not the other submissions beside it, not the other
children's scratch folders.
"""

from __future__ import annotations

import functools
import os
import sys
import sysconfig
import tempfile
from pathlib import Path

from plcsim.exercise.model import Exercise
from plcsim.grading.sandbox.importable import package_root

_PYTHON_PATHS = tuple(sysconfig.get_paths().values())
"""Computed once at import: sysconfig fills its caches lazily and not thread-safely, and a batch grades
from several threads (two threads in the first grade of a batch met "dictionary changed size")."""
_SYSTEM_READABLE = ("/usr", "/lib", "/lib64", "/etc", "/dev/null", "/dev/zero", "/dev/urandom")
"""Besides the Python installation and the loaded packages: shared libraries, configuration, devices."""


def readable_paths(exercise: Exercise, path: Path) -> list[str]:
    """What the child may read (a list of allowed files and folders, not of forbidden ones): the Python
    installation, the folders of the packages this process has loaded and the system's libraries; not
    the exercise's solutions, not the other files of the submission's folder (the other students'),
    not the temporary folder (the other children's scratch).

    The walk is cached (:func:`_granted`): the submissions of a batch share their folder, hidden
    folders and loaded packages, so it runs once per batch, not once per submission."""
    hidden = {s.path.resolve().parent for s in exercise.solutions}
    hidden |= {h.parent for h in hidden if h.parent.name == "solutions"}
    temp = Path(tempfile.gettempdir()).resolve()
    folder = path.resolve().parent  # its sub-folders may hold packages; its files are other submissions
    roots = {Path(p) for p in _SYSTEM_READABLE}
    roots |= {Path(p) for p in _PYTHON_PATHS}
    roots |= {package_root(m) for m in list(sys.modules.values())} - {None}  # type: ignore[arg-type]
    return list(_granted(folder, frozenset(hidden), temp, frozenset(roots)))


@functools.lru_cache(maxsize=32)
def _granted(folder: Path, hidden: frozenset[Path], temp: Path, roots: frozenset[Path]) -> tuple[str, ...]:
    """The trees below ``roots`` a child may read: each root whole, or, where it holds a hidden folder,
    the ``temp`` folder or the submissions' ``folder``, its other entries (never the files of ``folder``
    itself, never ``temp``).

    ``temp`` (where every child has its scratch) is left out of a root that holds it, but a root inside
    it is granted: a project cloned or installed under ``/tmp`` must still be importable by the child
    (hiding all of ``temp`` made every lazy import of such an installation fail after the lock-down)."""
    out: list[str] = []

    def within(inner: Path, outer: Path) -> bool:
        return inner == outer or outer in inner.parents

    def grant(p: Path) -> None:
        if p == temp or any(within(p, h) for h in hidden) or not p.exists():
            return
        if p.is_file() and p.parent == folder:
            return
        if not any(within(h, p) for h in hidden) and not within(temp, p) and not within(folder, p):
            out.append(str(p))
            return
        if p.is_dir():
            for child in p.iterdir():
                if not child.is_symlink():
                    grant(child)

    for root in sorted(roots):
        grant(root.resolve())
    granted = set(out)
    return tuple(sorted(g for g in granted if not _ancestors(g) & granted))  # one rule per granted tree


def _ancestors(path: str) -> set[str]:
    out, parent = set(), os.path.dirname(path)
    while parent and parent not in out and parent != path:
        out.add(parent)
        path, parent = parent, os.path.dirname(parent)
    return out
