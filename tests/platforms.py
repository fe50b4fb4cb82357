"""What a test needs of the system it runs on, said once: the markers that skip a test where the system
lacks what it checks (with the reason a reader of the CI log sees), and the helpers that make a test's own
assumptions hold on Linux, macOS and Windows alike.

plcsim runs on all three (.github/workflows/tests.yml runs the suite there). A test is marked only for
what the system cannot do, never for a bug: a test that fails on Windows because plcsim is wrong there must
fail, so that the CI shows it.
"""

from __future__ import annotations

import os
import sys
import sysconfig
from pathlib import Path

import pytest

LINUX = sys.platform.startswith("linux")
WINDOWS = os.name == "nt"
POSIX = os.name == "posix"
"""Linux and macOS: fork, signals, process groups, resource limits."""


def linux_only(reason: str) -> pytest.MarkDecorator:
    """Skip the test except on Linux, saying what of Linux's it needs (namespaces, Landlock, /proc ...)."""
    return pytest.mark.skipif(not LINUX, reason=f"Linux only: {reason}")


def posix_only(reason: str) -> pytest.MarkDecorator:
    """Skip the test on Windows, saying what of POSIX's it needs (fork, a signal, a resource limit ...)."""
    return pytest.mark.skipif(not POSIX, reason=f"POSIX only (not Windows): {reason}")


NAMESPACES = linux_only("the grading child's PID and network namespaces and Landlock")
PROC = linux_only("reads /proc")
SIGNALS = posix_only("kills with a POSIX signal (SIGKILL)")


def console_script(name: str) -> Path:
    """Where pip installed the console script ``name`` for this interpreter: ``bin/NAME`` on Linux and
    macOS, ``Scripts\\NAME.exe`` on Windows (not always beside ``python.exe`` there)."""
    return Path(sysconfig.get_path("scripts")) / (f"{name}.exe" if WINDOWS else name)


def utf8_env(**extra: str) -> dict[str, str]:
    """This process's environment for a child Python whose stdin, stdout, stderr and files are UTF-8
    whatever the system's code page (Windows' is cp1252): read its output with ``encoding="utf-8"``
    (:data:`UTF8`), not the locale's."""
    return {**os.environ, "PYTHONUTF8": "1", "PYTHONIOENCODING": "utf-8", **extra}


UTF8 = {"encoding": "utf-8", "errors": "strict"}
"""``subprocess.run(..., **UTF8)``: a child's output decoded as UTF-8 (``text=True`` alone decodes it in the
locale's code page, cp1252 on Windows)."""

WINDOWS_ROOT = {"SYSTEMROOT": os.environ["SYSTEMROOT"]} if "SYSTEMROOT" in os.environ else {}
"""What a child's minimal environment (``env={...}`` with nothing else) must keep on Windows: without
``SYSTEMROOT`` a child Python there cannot reach the system's random numbers or sockets."""
