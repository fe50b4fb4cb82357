"""``python -m plcsim`` imports nothing from the current folder.

``python -m`` puts the current folder first on ``sys.path`` (``cd submissions && python -m plcsim grade
4.3.5 .``): a submission saved there as ``numpy.py`` would be imported by the grader itself, unconfined,
in place of numpy. ``plcsim/__init__.py`` imports this module before anything else; it takes that entry
off the path again, unless the current folder is the source checkout plcsim itself runs from (its root
holds plcsim, plants and exercises). The grading children get a path without the current folder and
the submission's folder as well (:mod:`plcsim.grading.sandbox.parent`).
"""

from __future__ import annotations

import os
import sys

CHECKOUT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
"""The folder that holds this plcsim package (a source checkout's root, or site-packages)."""


def same_folder(a: str, b: str) -> bool:
    """True if two paths name the same folder (case-insensitively where the system is)."""
    return os.path.normcase(os.path.realpath(a)) == os.path.normcase(os.path.realpath(b))


def forget_current_folder() -> None:
    """Take the current folder off the front of ``sys.path`` where ``python -m`` put it."""
    if sys.argv[:1] != ["-m"] or not sys.path:  # not started with -m: whoever imports plcsim chose the path
        return
    cwd = os.getcwd()
    if same_folder(sys.path[0] or os.curdir, cwd) and not same_folder(cwd, CHECKOUT):
        del sys.path[0]


forget_current_folder()
