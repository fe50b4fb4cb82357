"""Run a submission in a fresh, confined child process and collect its raw results.

The child is ``python -m plcsim.sandbox_child`` (a new interpreter: nothing of the grader's state is
inherited), in its own session and process group, in a fresh scratch folder that is removed
afterwards, with limits it applies to itself before it loads the submission (:mod:`plcsim.confine`).
Its stdout and stderr are thrown away: only the result pipe counts, and what arrives there is
validated (:mod:`plcsim.run_result`) against what this process computed the exercise must produce.

The grader reads the pipe until the message is complete, the child has exited or the wall-time
limit has passed, never waiting for end-of-file (a grandchild may hold the pipe open); then it kills
the whole process group (and, through the PID namespace, everything the child started).
"""

from __future__ import annotations

import contextlib
import copy
import functools
import json
import os
import select
import shutil
import signal
import subprocess
import sys
import sysconfig
import tempfile
import threading
import time
import uuid
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from plcsim.errors import ConfigurationError
from plcsim.exercise import Exercise
from plcsim.program import Program
from plcsim.run_result import (
    EXTRA_COLUMNS,
    HEAD,
    MAX_HEADER_BYTES,
    Expected,
    InvalidResultError,
    RunResult,
    decode,
    message_length,
)
from plcsim.sandbox_child import MEMORY_EXIT, SIGNAL_EXIT_BASE

DEFAULT_ENTRY = "plcsim.sandbox_child"
POSIX = hasattr(os, "waitid") and hasattr(os, "killpg") and hasattr(os, "wait4")
"""Process groups, waitid and wait4 (Linux, macOS); otherwise (Windows) the portable, weaker path."""
EXIT_GRACE_S = 1.0
"""How long a child whose pipe closed without a result may take to exit and tell its exit status."""
_PROBE_PROGRAM = "def OB1(t):\n    pass\n"


@dataclass
class ChildOutcome:
    """What came of a child: the validated runs, or the kind and message of what went wrong."""

    runs: list[RunResult] = field(default_factory=list)
    kind: str | None = None
    message: str = ""
    notes: list[str] = field(default_factory=list)
    """The guards this system lacks (see :func:`gaps`)."""


_PREPARING = threading.Lock()
_PYTHON_PATHS = tuple(sysconfig.get_paths().values())
"""Computed once at import: sysconfig fills its caches lazily and not thread-safely, and a batch grades
from several threads (two threads in the first grade of a batch met "dictionary changed size")."""


def run_child(
    exercise: Exercise,
    path: Path,
    seed: int,
    scenarios: list[Any],
    limits: Any,
    *,
    geometry: bool = False,
    entry: str = DEFAULT_ENTRY,
    probes: Probes | None = None,
) -> ChildOutcome:
    """Run ``path`` on the scenarios in a confined child; its results, validated, or what went wrong.

    ``probes``: the batch's trusted probe results (:class:`Probes`), instead of probing again."""
    if not path.is_file():
        return ChildOutcome(kind="program error", message=f"cannot read program {path}: no such file")
    with _PREPARING:  # process-wide state (sys.modules, sysconfig's lazy caches): one batch thread at a time
        probes = probes or Probes(exercise.number, seed, {})
        expected = [probes.expected(exercise, s, seed) for s in scenarios]  # an exercise's mistake shows here
        module, attribute = _locate(exercise)
        readable = [str(path.resolve()), *_readable(exercise, path)]
    cap = MAX_HEADER_BYTES + sum(e.max_rows * (HEAD + len(e.kinds) + EXTRA_COLUMNS) * 8 for e in expected)
    scratch = tempfile.mkdtemp(prefix="plcsim-grade-")
    cgroup = _make_cgroup()
    request = {
        "module": module,
        "attribute": attribute,
        "path": str(path.resolve()),
        "seed": seed,
        "scenarios": [s.name for s in scenarios],
        "geometry": geometry,
        "limits": {"cpu_seconds": limits.cpu_seconds, "memory_mb": limits.memory_mb},
        "scratch": scratch,
        "cgroup": cgroup,
        "readable": readable,
    }
    try:
        run = _run_posix if POSIX else _run_portable
        buffer, problem, timed_out, status, cpu_s = run(entry, request, limits, cap)
    finally:
        _cleanup(scratch, cgroup)
    outcome = _interpret(buffer, problem, timed_out, status, cpu_s, expected, seed, limits)
    outcome.notes = gaps(cgroup)
    return outcome


def _interpret(
    buffer: bytes | None,
    problem: str | None,
    timed_out: bool,
    status: int,
    cpu_s: float,
    expected: list[Expected],
    seed: int,
    limits: Any,
) -> ChildOutcome:
    if problem is not None:
        return ChildOutcome(kind="invalid result", message=problem)
    if buffer is None:
        return _no_result(status, cpu_s, timed_out, limits)
    try:
        decoded = decode(buffer, expected, seed)
    except InvalidResultError as exc:
        return ChildOutcome(kind="invalid result", message=str(exc))
    if isinstance(decoded, tuple):
        return ChildOutcome(kind=decoded[0], message=decoded[1])
    return ChildOutcome(runs=decoded)


def _command(entry: str, request: dict[str, Any]) -> list[str]:
    return [sys.executable, "-B", "-m", entry, json.dumps(request)]


def _run_posix(entry: str, request: dict[str, Any], limits: Any, cap: int) -> tuple[Any, ...]:
    """The child in its own session, its result on a pipe: (message, problem, out of time, status, CPU s)."""
    read_end, write_end = os.pipe()
    request = {**request, "fd": write_end}
    try:
        proc = subprocess.Popen(
            _command(entry, request),
            cwd=request["scratch"],
            env=_child_env(request["scratch"]),
            stdin=subprocess.DEVNULL,
            stdout=subprocess.DEVNULL,
            stderr=subprocess.DEVNULL,
            pass_fds=(write_end,),
            start_new_session=True,
        )
    except OSError as exc:
        os.close(read_end)
        raise ConfigurationError(f"cannot start the grading child: {exc}") from None
    finally:
        os.close(write_end)
    try:
        buffer, problem, timed_out = _collect(proc, read_end, limits.wall_seconds, cap)
        if buffer is None and not timed_out:  # it ended by itself: let it report how, briefly
            _wait_exit(proc.pid, EXIT_GRACE_S)
    finally:
        os.close(read_end)
        _kill_group(proc.pid)
        status, cpu_s = _reap(proc)
    return buffer, problem, timed_out, status, cpu_s


def _run_portable(entry: str, request: dict[str, Any], limits: Any, cap: int) -> tuple[Any, ...]:
    """Windows (no process groups to kill, no select on pipes, no resource limits): the child writes its
    result to a file in scratch and is killed at the wall-time limit; what it starts may outlive it."""
    result = os.path.join(request["scratch"], "result.bin")
    proc = subprocess.Popen(
        _command(entry, {**request, "fd": None, "result_file": result}),
        cwd=request["scratch"],
        env=_child_env(request["scratch"]),
        stdin=subprocess.DEVNULL,
        stdout=subprocess.DEVNULL,
        stderr=subprocess.DEVNULL,
        creationflags=getattr(subprocess, "CREATE_NEW_PROCESS_GROUP", 0),
    )
    try:
        proc.wait(timeout=limits.wall_seconds)
    except subprocess.TimeoutExpired:
        proc.kill()
        proc.wait()
        return None, None, True, proc.returncode, 0.0
    if not os.path.exists(result):
        return None, None, False, proc.returncode, 0.0
    if os.path.getsize(result) > cap:
        return None, f"the child sent more than {cap} bytes", False, proc.returncode, 0.0
    with open(result, "rb") as f:
        return f.read(), None, False, proc.returncode, 0.0


def _collect(proc: subprocess.Popen, fd: int, wall_s: float, cap: int) -> tuple[bytes | None, str | None, bool]:
    """Read one message from ``fd``: (the message or None, a protocol problem or None, out of time?).

    It returns as soon as the message is complete, or the child has exited and the pipe holds nothing
    more (a grandchild holding the pipe open does not delay it), or the wall time is up."""
    os.set_blocking(fd, False)
    deadline = time.monotonic() + wall_s
    buffer = bytearray()
    total = None
    while True:
        remaining = deadline - time.monotonic()
        if remaining <= 0:
            return None, None, True
        gone = _exited(proc.pid)  # before select: what it wrote before exiting is readable now
        ready, _, _ = select.select([fd], [], [], min(remaining, 0.05))
        data = b""
        if ready:
            try:
                data = os.read(fd, 1 << 20)
                gone = gone or not data  # end of file: every writer is gone
            except BlockingIOError:
                pass
        buffer += data
        if data and total is None:
            try:
                total = message_length(buffer)
            except InvalidResultError as exc:
                return None, str(exc), False
            if total is not None and total > cap:
                return None, f"the child's result announces {total} bytes; at most {cap} are possible", False
        if total is not None and len(buffer) >= total:
            if len(buffer) > total:
                return None, f"the child sent {len(buffer) - total} bytes after its result", False
            return bytes(buffer), None, False
        if len(buffer) > cap:
            return None, f"the child sent more than {cap} bytes", False
        if gone and not data:
            return None, (f"the child's result is incomplete ({len(buffer)} bytes)" if buffer else None), False


def _kill_group(pgid: int) -> None:
    with contextlib.suppress(ProcessLookupError, PermissionError):
        os.killpg(pgid, signal.SIGKILL)


def _exited(pid: int) -> bool:
    """True once the child has ended; it is left unreaped, for :func:`_reap` to read its CPU time."""
    return os.waitid(os.P_PID, pid, os.WEXITED | os.WNOHANG | os.WNOWAIT) is not None


def _wait_exit(pid: int, seconds: float) -> None:
    deadline = time.monotonic() + seconds
    while not _exited(pid) and time.monotonic() < deadline:
        time.sleep(0.01)


def _reap(proc: subprocess.Popen) -> tuple[int, float]:
    """Wait for the child (already killed): its exit status and the CPU seconds it and its children used."""
    _, status, usage = os.wait4(proc.pid, 0)
    proc.returncode = os.waitstatus_to_exitcode(status)
    return proc.returncode, usage.ru_utime + usage.ru_stime


def _no_result(code: int, cpu_s: float, timed_out: bool, limits: Any) -> ChildOutcome:
    signum = -code if code < 0 else code - SIGNAL_EXIT_BASE if code > SIGNAL_EXIT_BASE else 0
    if timed_out:
        return ChildOutcome(kind="time limit", message=f"no result within {limits.wall_seconds:g} s of wall time")
    xcpu, kill = getattr(signal, "SIGXCPU", None), getattr(signal, "SIGKILL", None)
    if signum and (signum == xcpu or (signum == kill and cpu_s >= limits.cpu_seconds)):
        message = f"the submission used more than {limits.cpu_seconds} s of CPU time"
        return ChildOutcome(kind="time limit", message=message)
    if code == MEMORY_EXIT:
        message = f"the submission ran out of memory (the limit is {limits.memory_mb} MB)"
        return ChildOutcome(kind="memory limit", message=message)
    try:
        how = f"was killed by signal {signal.Signals(signum).name}" if signum > 0 else f"exited with code {code}"
    except ValueError:
        how = f"exited with code {code}"
    return ChildOutcome(kind="crash", message=f"the grading process {how} without sending a result")


def gaps(cgroup: str | None) -> list[str]:
    """The guards this system lacks, as warnings for the report (none on Linux with Landlock)."""
    if not POSIX:
        return [
            "sandbox: on this system the child runs without resource limits, process group or file "
            "confinement; only the wall-time limit applies (grade on Linux for untrusted submissions)"
        ]
    if not sys.platform.startswith("linux"):
        return [
            "sandbox: on this system the child has resource limits and is killed with its process group, "
            "but no namespaces or Landlock: it may read and write wherever the grading user may"
        ]
    if os.geteuid() == 0 and cgroup is None:
        return ["sandbox: running as root without a writable pids cgroup, the number of processes is not limited"]
    return []


@dataclass(frozen=True)
class Probes:
    """The trusted probe's results of one batch, computed once per (exercise, scenario, seed) in the
    grader (:meth:`of`) instead of once per submission.

    Each submission is validated against its own deep copy (:meth:`expected`), so nothing done while
    grading one submission can change what the next is checked against; what a child sends never
    reaches them. A scenario or seed the batch did not probe is probed afresh.
    """

    exercise: str
    seed: int
    by_scenario: Mapping[str, Expected]
    """Scenario name -> what its run must look like."""

    @classmethod
    def of(cls, exercise: Exercise, scenarios: Sequence[Any], seed: int) -> Probes:
        return cls(exercise.number, seed, {s.name: _expected(exercise, s, seed) for s in scenarios})

    def expected(self, exercise: Exercise, scenario: Any, seed: int) -> Expected:
        """What the run of ``scenario`` must look like: a copy of the cached probe, or a fresh probe."""
        ours = (exercise.number, seed) == (self.exercise, self.seed)
        cached = self.by_scenario.get(scenario.name) if ours else None
        return copy.deepcopy(cached) if cached is not None else _expected(exercise, scenario, seed)


def _expected(exercise: Exercise, scenario: Any, seed: int) -> Expected:
    """What the run of ``scenario`` must look like, from a trusted probe program on the same CPU and rig."""
    sim = exercise.simulation(Program.from_source(_PROBE_PROGRAM, "<probe>"), scenario, seed=seed)
    trace = sim.trace
    step = max(1, min(sim.dt_ns, trace.meta.get("cycle_ns") or sim.dt_ns))
    duration = scenario.duration_ns
    max_rows = max(4 * (duration // step + 1), 2 * (duration // 100_000 + 1)) + 10_000
    meta = {k: v for k, v in trace.meta.items() if k not in ("end_ns", "scans", "program")}
    return Expected(scenario.name, duration, max_rows, dict(trace.kinds), dict(trace.types), meta)


def _locate(exercise: Exercise) -> tuple[str, str]:
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


_SYSTEM_READABLE = ("/usr", "/lib", "/lib64", "/etc", "/dev/null", "/dev/zero", "/dev/urandom")
"""Besides the Python installation and the loaded packages: shared libraries, configuration, devices."""


def _readable(exercise: Exercise, path: Path) -> list[str]:
    """What the child may read (a list of allowed files and folders, not of forbidden ones): the Python
    installation, the folders of the packages this process has loaded and the system's libraries; not
    the exercise's solutions, not the other files of the submission's folder (the other students'),
    not the temporary folder (the other children's scratch).

    The walk is cached (:func:`_granted`): the submissions of a batch share their folder, hidden
    folders and loaded packages, so it runs once per batch, not once per submission."""
    hidden = {s.path.resolve().parent for s in exercise.solutions}
    hidden |= {h.parent for h in hidden if h.parent.name == "solutions"}
    hidden.add(Path(tempfile.gettempdir()).resolve())
    folder = path.resolve().parent  # its sub-folders may hold packages; its files are other submissions
    roots = {Path(p) for p in _SYSTEM_READABLE}
    roots |= {Path(p) for p in _PYTHON_PATHS}
    roots |= {_package_root(m) for m in list(sys.modules.values())} - {None}  # type: ignore[arg-type]
    return list(_granted(folder, frozenset(hidden), frozenset(roots)))


@functools.lru_cache(maxsize=32)
def _granted(folder: Path, hidden: frozenset[Path], roots: frozenset[Path]) -> tuple[str, ...]:
    """The trees below ``roots`` a child may read: each root whole, or, where it holds a hidden folder or
    the submissions' ``folder``, its other entries (never the files of ``folder`` itself)."""
    out: list[str] = []

    def within(inner: Path, outer: Path) -> bool:
        return inner == outer or outer in inner.parents

    def grant(p: Path) -> None:
        if any(within(p, h) for h in hidden) or not p.exists():
            return
        if p.is_file() and p.parent == folder:
            return
        if not any(within(h, p) for h in hidden) and not within(folder, p):
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


def _package_root(module: Any) -> Path | None:
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


def _child_env(scratch: str) -> dict[str, str]:
    paths = [os.path.abspath(p or os.getcwd()) for p in sys.path]
    return {
        "PATH": os.environ.get("PATH", "/usr/bin:/bin"),
        "PYTHONPATH": os.pathsep.join(p for p in paths if os.path.exists(p)),
        "PYTHONHASHSEED": "0",
        "PYTHONDONTWRITEBYTECODE": "1",
        "HOME": scratch,
        "TMPDIR": scratch,
        "OPENBLAS_NUM_THREADS": "1",
        "OMP_NUM_THREADS": "1",
        "MKL_NUM_THREADS": "1",
        "MPLBACKEND": "Agg",
        **({"SYSTEMROOT": os.environ["SYSTEMROOT"]} if "SYSTEMROOT" in os.environ else {}),
    }


_CGROUP_ROOTS = ("/sys/fs/cgroup/pids", "/sys/fs/cgroup")


def _make_cgroup() -> str | None:
    """For root (whom RLIMIT_NPROC does not bind), a ``pids`` cgroup allowing no new process."""
    if not hasattr(os, "geteuid") or os.geteuid() != 0:
        return None
    for root in _CGROUP_ROOTS:
        path = os.path.join(root, f"plcsim-{os.getpid()}-{uuid.uuid4().hex[:12]}")
        try:
            os.mkdir(path)
        except OSError:
            continue
        try:
            with open(os.path.join(path, "pids.max"), "w") as f:
                f.write("1")
            return path
        except OSError:
            with contextlib.suppress(OSError):
                os.rmdir(path)
    return None


def _cleanup(scratch: str, cgroup: str | None) -> None:
    shutil.rmtree(scratch, ignore_errors=True)
    if cgroup is not None:
        for _ in range(50):  # the cgroup is empty once the killed processes are reaped
            try:
                os.rmdir(cgroup)
                break
            except OSError:
                time.sleep(0.01)
