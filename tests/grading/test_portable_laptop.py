"""Any laptop: plcsim on an interpreter that looks like Windows' (no ``resource``, ``fcntl``, ``pwd`` ...
for plcsim's own modules, no ``os.fork``, ``setsid``, ``killpg``, ``waitid``, ``wait4``, ``getuid``)
imports every module and grades in the sandbox, and the command's output survives a cp1252 console.

The look of Windows comes from a ``sitecustomize`` module on PYTHONPATH, which the grading child
inherits too (the grader passes its ``sys.path`` on), so both sides run without the Unix-only parts.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]

WINDOWS_LIKE = """
import builtins, os
UNIX_ONLY = {"resource", "fcntl", "termios", "pwd", "grp", "pty", "tty", "syslog"}
OURS = {"plcsim", "plants", "exercises"}
_import = builtins.__import__

def windows_import(name, globals=None, locals=None, fromlist=(), level=0):
    caller = (globals or {}).get("__name__", "")
    if level == 0 and name.partition(".")[0] in UNIX_ONLY and caller.partition(".")[0] in OURS:
        raise ModuleNotFoundError(f"No module named {name!r} (as on Windows; imported by {caller})")
    return _import(name, globals, locals, fromlist, level)

builtins.__import__ = windows_import  # third-party packages keep their own platform checks
for name in ("fork", "forkpty", "setsid", "killpg", "waitid", "wait4", "getuid", "geteuid", "setpgrp", "getpgid"):
    if hasattr(os, name):
        delattr(os, name)
"""

PROBE = """
import importlib, json, os, pkgutil, sys
import plcsim, plants, exercises
failed = {}
for package in (plcsim, plants, exercises):
    for module in pkgutil.walk_packages(package.__path__, package.__name__ + "."):
        if not module.name.endswith("__main__"):
            try:
                importlib.import_module(module.name)
            except Exception as exc:
                failed[module.name] = repr(exc)
from exercises import get
from plcsim.grading.sandbox import parent as sandbox
from plcsim.grading.grader import grade_sandboxed
ex = get("4.3.1")
good = grade_sandboxed(ex, ex.reference.path)
wrong = grade_sandboxed(ex, ex.solution("wrong-latch").path)
print(json.dumps({
    "fork": hasattr(os, "fork"), "posix": sandbox.POSIX, "failed": failed,
    "good": [good.error, good.score, good.max_score], "wrong": [wrong.error, wrong.score],
    "notes": good.warnings,
}))
"""


def _run(args: list[str], tmp_path: Path, **env: str) -> subprocess.CompletedProcess:
    paths = [str(tmp_path), str(ROOT), *sys.path]
    full = {**os.environ, "PYTHONPATH": os.pathsep.join(paths), **env}
    return subprocess.run(args, capture_output=True, cwd=tmp_path, env=full, timeout=300, check=False)


def test_on_an_interpreter_without_the_unix_only_parts_every_module_imports_and_grading_works(tmp_path):
    (tmp_path / "sitecustomize.py").write_text(WINDOWS_LIKE, encoding="utf-8")
    done = _run([sys.executable, "-c", PROBE], tmp_path)
    assert done.returncode == 0, done.stderr.decode()
    seen = json.loads(done.stdout.decode().strip().splitlines()[-1])
    assert (seen["fork"], seen["posix"], seen["failed"]) == (False, False, {})
    assert seen["good"] == [None, 3.0, 3.0]
    assert seen["wrong"][0] is None and seen["wrong"][1] < 3.0
    assert seen["notes"][0].startswith("sandbox: portable path")


@pytest.mark.parametrize(
    ("args", "code", "marks"),
    [
        (["grade", "4.3.1", "--reference"], 0, ["+ presses: 3/3 checks passed", "PASSED  score 3 / 3"]),
        (["grade", "4.3.1", "--solution", "wrong-latch"], 1, ["x presses: 0/3 checks passed", "FAILED  score"]),
        (["run", "4.3.1", "--reference"], 0, ["  + LED equals the button in every scan"]),
    ],
    ids=["grade-passed", "grade-failed", "run"],
)
def test_a_cp1252_console_gets_ascii_marks_and_the_true_exit_code(tmp_path, args, code, marks):
    done = _run([sys.executable, "-m", "plcsim", *args], tmp_path, PYTHONIOENCODING="cp1252", COLUMNS="100")
    assert done.returncode == code, done.stderr.decode("cp1252")
    text = done.stdout.decode("cp1252")
    for mark in marks:
        assert mark in text
    assert "✓" not in text and "✗" not in text
