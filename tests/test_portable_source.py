"""plcsim's own code (plcsim/, plants/, exercises/) runs the same on Linux, macOS and Windows, checked in its
source where no Windows machine is at hand:

* every file it opens as text names its encoding: without one, Python uses the locale's (cp1252 on a
  Windows laptop), and a program, exercise or report with a non-ASCII name (``Dopravník``) reads or
  writes differently there;
* a name only POSIX has (``os.fork``, ``signal.SIGKILL``, ``resource``, ``fcntl`` ...) appears only in the
  modules that guard it (:data:`GUARDED`): elsewhere it would be an AttributeError or ImportError on Windows.

tests/grading/test_portable_laptop.py proves the guarded modules import and grade on an interpreter without
the POSIX-only parts.
"""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent
PACKAGES = ("plcsim", "plants", "exercises")

POSIX_ONLY_OS = {
    "fork", "forkpty", "setsid", "setpgrp", "setpgid", "getpgid", "getpgrp", "killpg", "getuid", "geteuid",
    "getgid", "getppid", "uname", "wait3", "wait4", "waitid", "WNOHANG", "WNOWAIT", "WEXITED", "P_PID",
    "WIFEXITED", "WIFSIGNALED", "WEXITSTATUS", "WTERMSIG", "O_PATH", "O_CLOEXEC", "sched_getaffinity",
    "sched_setaffinity", "getloadavg", "mkfifo", "pipe2", "set_blocking", "nice", "statvfs",
}  # fmt: skip
POSIX_ONLY_SIGNAL = {
    "SIGKILL", "SIGXCPU", "SIGALRM", "SIGHUP", "SIGUSR1", "SIGUSR2", "SIGCHLD", "SIGSTOP", "SIGCONT", "SIGQUIT",
    "SIGPIPE", "alarm", "setitimer", "pthread_kill", "pthread_sigmask", "siginterrupt",
}  # fmt: skip
POSIX_ONLY_MODULES = {"resource", "fcntl", "termios", "pwd", "grp", "pty", "tty", "syslog", "posix"}

GUARDED = {
    "plcsim/grading/sandbox/forkserver.py": "used only where forkserver.enabled() (Linux)",
    "plcsim/grading/sandbox/child.py": "forks only once confine.enter_namespaces() succeeded (Linux)",
    "plcsim/grading/sandbox/confine.py": "each guard checks the platform or catches the ImportError",
    "plcsim/grading/sandbox/parent.py": "the POSIX path runs only where parent.POSIX; gaps() checks Linux first",
}
"""The modules allowed POSIX-only names, and the guard that keeps each off Windows."""


def sources() -> list[Path]:
    return sorted(p for package in PACKAGES for p in (ROOT / package).rglob("*.py") if "solutions" not in p.parts)


def _constant(node: ast.AST | None) -> object:
    return node.value if isinstance(node, ast.Constant) else None


def _keyword(call: ast.Call, name: str) -> ast.AST | None:
    return next((k.value for k in call.keywords if k.arg == name), None)


def text_without_encoding(call: ast.Call) -> str | None:
    """What ``call`` opens as text in the locale's encoding (an ``open``, ``Path.open``, ``read_text``,
    ``write_text`` or a ``subprocess`` call in text mode, without ``encoding=``), or None."""
    func = call.func
    name = func.attr if isinstance(func, ast.Attribute) else func.id if isinstance(func, ast.Name) else ""
    owner = func.value.id if isinstance(func, ast.Attribute) and isinstance(func.value, ast.Name) else None
    if _keyword(call, "encoding") is not None:
        return None
    if name == "read_text" and not call.args:
        return "read_text() without encoding"
    if name == "write_text" and len(call.args) < 2:
        return "write_text() without encoding"
    if name == "open" and owner not in ("os", "webbrowser"):
        at = 1 if isinstance(func, ast.Name) or owner == "io" else 0  # open(path, mode) / path.open(mode)
        mode = call.args[at] if len(call.args) > at else _keyword(call, "mode")
        if mode is None or "b" not in str(_constant(mode) or ""):
            return f"open(mode={_constant(mode) or 'r'!r}) in text mode without encoding"
    if owner == "subprocess" and any(_constant(_keyword(call, k)) is True for k in ("text", "universal_newlines")):
        return f"subprocess.{name}(text=True) without encoding"
    return None


def posix_only_name(node: ast.AST) -> str | None:
    """The POSIX-only name ``node`` uses, or None."""
    if isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name):
        if node.value.id == "os" and node.attr in POSIX_ONLY_OS:
            return f"os.{node.attr}"
        if node.value.id == "signal" and node.attr in POSIX_ONLY_SIGNAL:
            return f"signal.{node.attr}"
    if isinstance(node, ast.Import | ast.ImportFrom):
        modules = [a.name for a in node.names] if isinstance(node, ast.Import) else [node.module or ""]
        used = [m for m in modules if m.partition(".")[0] in POSIX_ONLY_MODULES]
        return f"import {used[0]}" if used else None
    return None


def findings(path: Path) -> tuple[list[str], list[str]]:
    """(text opened without an encoding, POSIX-only names) in one file, as ``file:line: what``."""
    where = path.relative_to(ROOT).as_posix()
    tree = ast.parse(path.read_text(encoding="utf-8"), filename=where)
    texts, names = [], []
    for node in ast.walk(tree):
        if isinstance(node, ast.Call) and (what := text_without_encoding(node)):
            texts.append(f"{where}:{node.lineno}: {what}")
        if what := posix_only_name(node):
            names.append(f"{where}:{node.lineno}: {what}")
    return texts, names


def test_every_file_opened_as_text_names_its_encoding():
    found = [line for path in sources() for line in findings(path)[0]]
    assert found == [], "pass encoding='utf-8' (the locale's is cp1252 on Windows):\n" + "\n".join(found)


def test_posix_only_names_appear_only_in_the_modules_that_guard_them():
    found = [
        line for path in sources() if path.relative_to(ROOT).as_posix() not in GUARDED for line in findings(path)[1]
    ]
    assert found == [], "Windows has none of these; guard them as plcsim/grading/sandbox does:\n" + "\n".join(found)


@pytest.mark.parametrize("module", sorted(GUARDED))
def test_each_guarded_module_still_needs_its_exemption(module):
    """An exemption that no longer exempts anything goes (else a new POSIX-only name there is never seen)."""
    assert findings(ROOT / module)[1], f"{module} uses no POSIX-only name any more: remove it from GUARDED"


@pytest.mark.parametrize(
    ("source", "found"),
    [
        ("open(p)", "open(mode='r') in text mode without encoding"),
        ("open(p, 'w')", "open(mode='w') in text mode without encoding"),
        ("path.open('a')", "open(mode='a') in text mode without encoding"),
        ("Path(p).read_text()", "read_text() without encoding"),
        ("p.write_text(s)", "write_text() without encoding"),
        ("subprocess.run(a, text=True)", "subprocess.run(text=True) without encoding"),
        ("open(p, 'rb')", None),
        ("path.open('wb')", None),
        ("open(p, 'w', encoding='utf-8')", None),
        ("p.read_text(encoding='utf-8')", None),
        ("p.write_text(s, 'utf-8')", None),
        ("os.open(p, os.O_RDONLY)", None),
        ("webbrowser.open(url)", None),
        ("subprocess.run(a, capture_output=True)", None),
    ],
)
def test_the_scan_sees_text_opened_in_the_locales_encoding(source, found):
    call = next(n for n in ast.walk(ast.parse(source)) if isinstance(n, ast.Call))  # the outermost call
    assert text_without_encoding(call) == found


@pytest.mark.parametrize(
    ("source", "found"),
    [
        ("os.fork()", "os.fork"),
        ("os.killpg(pid, signal.SIGKILL)", "os.killpg"),
        ("signal.SIGKILL", "signal.SIGKILL"),
        ("import resource", "import resource"),
        ("from fcntl import flock", "import fcntl"),
        ("os.getpid()", None),
        ("signal.SIGTERM", None),
        ("import os.path", None),
    ],
)
def test_the_scan_sees_posix_only_names(source, found):
    first = [what for n in ast.walk(ast.parse(source)) if (what := posix_only_name(n))]
    assert (first[0] if first else None) == found
