"""Run a submission in a fresh, confined child process and collect its raw results.

The child is ``python -m plcsim.grading.sandbox.child`` (never a fork of the grader: nothing of its state is
inherited; on Linux forked from a clean fork server, :mod:`plcsim.grading.sandbox.forkserver`, which spares each child
the imports), in its own session and process group, in a fresh scratch folder that is removed
afterwards, with limits it applies to itself before it loads the submission (:mod:`plcsim.grading.sandbox.confine`).
Its stdout and stderr are thrown away: only the result pipe counts, and what arrives there is
validated (:mod:`plcsim.grading.run_result`) against what this process computed the exercise must produce
(the trusted probe, :mod:`plcsim.grading.sandbox.probes`). What the child may read is listed here too
(:mod:`plcsim.grading.sandbox.readable`) and sent along with the request.

The grader reads the pipe until the message is complete, the child has exited or the wall-time
limit has passed, never waiting for end-of-file (a grandchild may hold the pipe open); then it kills
the whole process group (and, through the PID namespace, everything the child started).

Where none of that exists (Windows), or with ``PLCSIM_SANDBOX=portable`` on any system, the portable
path runs the child without any of it and watches it from outside (:mod:`plcsim.grading.sandbox.watchdog`).
"""

from __future__ import annotations

import contextlib
import functools
import json
import os
import select
import shutil
import signal
import subprocess
import sys
import tempfile
import threading
import time
import uuid
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from plcsim.core.errors import ConfigurationError
from plcsim.exercise.model import Exercise
from plcsim.grading.run_result import (
    EXTRA_COLUMNS,
    HEAD,
    MAX_HEADER_BYTES,
    Expected,
    InvalidResultError,
    RunResult,
    decode,
    message_length,
)
from plcsim.grading.sandbox import forkserver
from plcsim.grading.sandbox.exits import MEMORY_EXIT, SIGNAL_EXIT_BASE
from plcsim.grading.sandbox.importable import locate
from plcsim.grading.sandbox.limits import Limits
from plcsim.grading.sandbox.probes import Probes
from plcsim.grading.sandbox.readable import readable_paths

DEFAULT_ENTRY = "plcsim.grading.sandbox.child"
TOO_SLOW = "too slow"
"""The outcome of a submission stopped at its exercise's CPU budget (:class:`~plcsim.grading.sandbox.limits.Budget`)."""
POSIX = hasattr(os, "waitid") and hasattr(os, "killpg") and hasattr(os, "wait4")
"""Process groups, waitid and wait4 (Linux, macOS); otherwise (Windows) the portable, weaker path."""
MODE_VARIABLE = "PLCSIM_SANDBOX"
"""``PLCSIM_SANDBOX=portable`` takes the portable path on any system (to prove it on Linux)."""
EXIT_GRACE_S = 1.0
"""How long a child whose pipe closed without a result may take to exit and tell its exit status."""


@dataclass
class ChildOutcome:
    """What came of a child: the validated runs, or the kind and message of what went wrong."""

    runs: list[RunResult] = field(default_factory=list)
    kind: str | None = None
    message: str = ""
    notes: list[str] = field(default_factory=list)
    """The guards this system lacks (see :func:`gaps`)."""


_PREPARING = threading.Lock()


def portable_mode() -> bool:
    """True where the child gets no POSIX confinement: on Windows, or with ``PLCSIM_SANDBOX=portable``.

    The portable path disables every Unix-only part (resource limits, process groups, namespaces,
    Landlock, cgroups, fork); the grader then watches the child from outside
    (:mod:`plcsim.grading.sandbox.watchdog`)."""
    mode = os.environ.get(MODE_VARIABLE, "").strip().lower()
    if mode not in ("", "confined", "portable"):
        raise ConfigurationError(
            f"{MODE_VARIABLE}={os.environ[MODE_VARIABLE]!r} is not a sandbox mode; use 'portable' or leave it unset"
        )
    return mode == "portable" or not POSIX


def run_child(
    exercise: Exercise,
    path: Path,
    seed: int,
    scenarios: list[Any],
    limits: Limits,
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
        module, attribute = locate(exercise)
        readable = [str(path.resolve()), *readable_paths(exercise, path)]
    cap = MAX_HEADER_BYTES + sum(e.max_rows * (HEAD + len(e.kinds) + EXTRA_COLUMNS) * 8 for e in expected)
    portable = portable_mode()
    scratch = tempfile.mkdtemp(prefix="plcsim-grade-")
    cgroup = None if portable else _make_cgroup()
    request = {
        "module": module,
        "attribute": attribute,
        "path": str(path.resolve()),
        "seed": seed,
        "scenarios": [s.name for s in scenarios],
        "geometry": geometry,
        "limits": {"cpu_seconds": limits.cpu_limit, "memory_mb": limits.memory_mb},
        "scratch": scratch,
        "cgroup": cgroup,
        "readable": readable,
        "confine": not portable,
    }
    try:
        run = _run_portable if portable else _run_posix
        buffer, problem, stopped, status, cpu_s = run(entry, request, limits, cap)
    finally:
        _cleanup(scratch, cgroup)
    outcome = _interpret(buffer, problem, stopped, status, cpu_s, expected, seed, limits)
    outcome.notes = gaps(cgroup, portable)
    return outcome


def _interpret(
    buffer: bytes | None,
    problem: str | None,
    stopped: str | None,
    status: int,
    cpu_s: float,
    expected: list[Expected],
    seed: int,
    limits: Any,
) -> ChildOutcome:
    if problem is not None:
        return ChildOutcome(kind="invalid result", message=problem)
    if buffer is None:
        return _no_result(status, cpu_s, stopped, limits)
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
    """The child in its own session, its result on a pipe: (message, problem, limit passed, status, CPU s).

    The limit passed is ``wall`` or, where the grader watches the memory from outside (macOS), ``memory``."""
    read_end, write_end = os.pipe()
    try:
        child = _start_posix(entry, request, write_end)
    except BaseException:
        os.close(read_end)
        raise
    finally:
        os.close(write_end)
    watch = _outside_watch(child.pid, limits)
    try:
        buffer, problem, stopped = _collect(child.exited, read_end, limits.wall_seconds, cap, watch)
        if buffer is None and not stopped:  # it ended by itself: let it report how, briefly
            _wait_exit(child.exited, EXIT_GRACE_S)
    finally:
        os.close(read_end)
        _kill_group(child.pid)
        if watch is not None:
            watch.kill_all()
        status, cpu_s = child.reap()
    return buffer, problem, stopped, status, cpu_s


@dataclass
class _PosixChild:
    """A started child: its pid (which is its process group), whether it ended, and its reaping."""

    pid: int
    exited: Callable[[], bool]
    reap: Callable[[], tuple[int, float]]
    """Wait for it (killed): its exit code (negative: the signal that killed it) and the CPU seconds it used."""


def _start_posix(entry: str, request: dict[str, Any], write_end: int) -> _PosixChild:
    """Fork the child from this process's fork server (:mod:`plcsim.grading.sandbox.forkserver`, Linux), or else start
    a fresh interpreter; a server that fails is replaced by a fresh start, never by a failed grade."""
    env = _child_env(request)
    if forkserver.enabled():
        try:
            server = forkserver.shared({k: v for k, v in env.items() if k not in _PER_CHILD_ENV})
            pid = server.spawn(entry, request, env, request["scratch"], write_end)
            return _PosixChild(pid, functools.partial(server.exited, pid), functools.partial(server.reap, pid))
        except (forkserver.ForkServerError, OSError):
            pass
    try:
        proc = subprocess.Popen(
            _command(entry, {**request, "fd": write_end}),
            cwd=request["scratch"],
            env=env,
            stdin=subprocess.DEVNULL,
            stdout=subprocess.DEVNULL,
            stderr=subprocess.DEVNULL,
            pass_fds=(write_end,),
            start_new_session=True,
        )
    except OSError as exc:
        raise ConfigurationError(f"cannot start the grading child: {exc}") from None
    return _PosixChild(proc.pid, functools.partial(_exited, proc.pid), functools.partial(_reap, proc))


_PER_CHILD_ENV = ("HOME", "TMPDIR", "TEMP", "TMP")
"""The variables of a child's environment that name its own scratch folder (not the fork server's)."""


def _run_portable(entry: str, request: dict[str, Any], limits: Any, cap: int) -> tuple[Any, ...]:
    """No process groups, no select on pipes, no resource limits (Windows, or ``PLCSIM_SANDBOX=portable``):
    the child writes its result to a file in scratch, and the grader watches the child and what it starts
    from outside (:mod:`plcsim.grading.sandbox.watchdog`), killing them all at the wall-time, CPU-time or
    memory limit or when the result file grows past what any result can hold. The child's stdin is a pipe the grader
    holds open: the child ends itself when it closes (the grader ended)."""
    from plcsim.grading.sandbox.watchdog import POLL_S, TreeWatch

    result = os.path.join(request["scratch"], "result.bin")
    proc = subprocess.Popen(
        _command(entry, {**request, "fd": None, "result_file": result}),
        cwd=request["scratch"],
        env=_child_env(request),
        stdin=subprocess.PIPE,
        stdout=subprocess.DEVNULL,
        stderr=subprocess.DEVNULL,
        creationflags=getattr(subprocess, "CREATE_NEW_PROCESS_GROUP", 0),
    )
    watch = TreeWatch(proc.pid, limits.cpu_limit, limits.memory_mb, result_file=result, max_bytes=cap)
    deadline = time.monotonic() + limits.wall_seconds
    stopped = None
    try:
        while stopped is None:
            try:
                proc.wait(timeout=POLL_S)
                break
            except subprocess.TimeoutExpired:
                stopped = "wall" if time.monotonic() >= deadline else watch.check()
    finally:
        watch.kill_all()
        with contextlib.suppress(OSError):
            proc.kill()  # in case the watch could not reach it
        proc.wait()
        with contextlib.suppress(OSError):
            proc.stdin.close()  # type: ignore[union-attr]
    if stopped == "output":
        return None, f"the child sent more than {cap} bytes", None, proc.returncode, watch.cpu_s
    if stopped is not None or not os.path.exists(result):
        return None, None, stopped, proc.returncode, watch.cpu_s
    if os.path.getsize(result) > cap:
        return None, f"the child sent more than {cap} bytes", None, proc.returncode, watch.cpu_s
    with open(result, "rb") as f:
        buffer, problem = _whole_message(f.read(), cap)
    return buffer, problem, None, proc.returncode, watch.cpu_s


def _whole_message(buffer: bytes, cap: int) -> tuple[bytes | None, str | None]:
    """A result read whole (from a file): the message, or the problem :func:`_collect` names on a pipe."""
    try:
        total = message_length(buffer)
    except InvalidResultError as exc:
        return None, str(exc)
    if total is not None and total > cap:
        return None, f"the child's result announces {total} bytes; at most {cap} are possible"
    if total is None or len(buffer) < total:
        return None, f"the child's result is incomplete ({len(buffer)} bytes)"
    if len(buffer) > total:
        return None, f"the child sent {len(buffer) - total} bytes after its result"
    return buffer, None


def _outside_watch(pid: int, limits: Any) -> Any:
    """The grader's watch over the limits this POSIX system does not enforce in the child (macOS: memory),
    or None where it enforces all (Linux)."""
    from plcsim.grading.sandbox.watchdog import TreeWatch, outside_limits

    cpu, memory = outside_limits(portable=False)
    if not (cpu or memory):
        return None
    return TreeWatch(pid, limits.cpu_limit if cpu else None, limits.memory_mb if memory else None)


def _collect(
    exited: Callable[[], bool], fd: int, wall_s: float, cap: int, watch: Any = None
) -> tuple[bytes | None, str | None, str | None]:
    """Read one message from ``fd``: (the message or None, a protocol problem or None, the limit passed).

    It returns as soon as the message is complete, or the child has exited and the pipe holds nothing
    more (a grandchild holding the pipe open does not delay it), or the wall time is up (``wall``), or
    the outside ``watch`` (if any) saw a limit passed."""
    os.set_blocking(fd, False)
    deadline = time.monotonic() + wall_s
    buffer = bytearray()
    total = None
    while True:
        remaining = deadline - time.monotonic()
        if remaining <= 0:
            return None, None, "wall"
        passed = watch.check() if watch is not None else None
        if passed is not None:
            return None, None, passed
        gone = exited()  # before select: what it wrote before exiting is readable now
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
                return None, str(exc), None
            if total is not None and total > cap:
                return None, f"the child's result announces {total} bytes; at most {cap} are possible", None
        if total is not None and len(buffer) >= total:
            if len(buffer) > total:
                return None, f"the child sent {len(buffer) - total} bytes after its result", None
            return bytes(buffer), None, None
        if len(buffer) > cap:
            return None, f"the child sent more than {cap} bytes", None
        if gone and not data:
            return None, (f"the child's result is incomplete ({len(buffer)} bytes)" if buffer else None), None


def _kill_group(pgid: int) -> None:
    with contextlib.suppress(ProcessLookupError, PermissionError):
        os.killpg(pgid, signal.SIGKILL)


def _exited(pid: int) -> bool:
    """True once the child has ended; it is left unreaped, for :func:`_reap` to read its CPU time."""
    return os.waitid(os.P_PID, pid, os.WEXITED | os.WNOHANG | os.WNOWAIT) is not None


def _wait_exit(exited: Callable[[], bool], seconds: float) -> None:
    deadline = time.monotonic() + seconds
    while not exited() and time.monotonic() < deadline:
        time.sleep(0.01)


def _reap(proc: subprocess.Popen) -> tuple[int, float]:
    """Wait for the child (already killed): its exit status and the CPU seconds it and its children used."""
    _, status, usage = os.wait4(proc.pid, 0)
    proc.returncode = os.waitstatus_to_exitcode(status)
    return proc.returncode, usage.ru_utime + usage.ru_stime


def _no_result(code: int, cpu_s: float, stopped: str | None, limits: Any) -> ChildOutcome:
    """What a child that sent no result came to: ``stopped`` names the limit the grader stopped it at."""
    signum = -code if code < 0 else code - SIGNAL_EXIT_BASE if code > SIGNAL_EXIT_BASE else 0
    if stopped == "wall":
        return ChildOutcome(kind="time limit", message=f"no result within {limits.wall_seconds:g} s of wall time")
    xcpu, kill = getattr(signal, "SIGXCPU", None), getattr(signal, "SIGKILL", None)
    if stopped == "cpu" or (signum and (signum == xcpu or (signum == kill and cpu_s >= limits.cpu_limit))):
        if limits.budget_binds:
            return ChildOutcome(kind=TOO_SLOW, message=limits.budget.too_slow())
        message = f"the submission used more than {limits.cpu_seconds} s of CPU time"
        return ChildOutcome(kind="time limit", message=message)
    if stopped == "memory" or code == MEMORY_EXIT:
        message = f"the submission ran out of memory (the limit is {limits.memory_mb} MB)"
        return ChildOutcome(kind="memory limit", message=message)
    try:
        how = f"was killed by signal {signal.Signals(signum).name}" if signum > 0 else f"exited with code {code}"
    except ValueError:
        how = f"exited with code {code}"
    return ChildOutcome(kind="crash", message=f"the grading process {how} without sending a result")


def gaps(cgroup: str | None, portable: bool = False) -> list[str]:
    """The guards this system lacks, as warnings for the report (none on Linux with Landlock)."""
    if portable:
        return [
            "sandbox: portable path (no resource limits, process group, namespaces or file confinement in the "
            "child): the grader watches its wall time, CPU time and memory from outside and kills it with the "
            "processes it saw it start; the submission may read and write wherever the grading user may "
            "(grade on Linux for untrusted submissions)"
        ]
    if not sys.platform.startswith("linux"):
        return [
            "sandbox: on this system the child has resource limits (memory watched by the grader) and is killed "
            "with its process group, but no namespaces or Landlock: it may read and write wherever the grading "
            "user may"
        ]
    if os.geteuid() == 0 and cgroup is None:
        return ["sandbox: running as root without a writable pids cgroup, the number of processes is not limited"]
    return []


def child_path(submission: str, module: str) -> list[str]:
    """The child's ``PYTHONPATH``: this process's path without the current folder and the submission's
    folder (a submission there saved as ``numpy.py`` would be imported in place of numpy, before the child
    confines itself), unless plcsim or the exercise's package is imported from there."""
    from plcsim.core.startup import same_folder
    from plcsim.grading.sandbox.importable import package_root

    needed = [root.parent for root in map(package_root, (sys.modules["plcsim"], sys.modules[module])) if root]
    untrusted = [os.getcwd(), os.path.dirname(os.path.abspath(submission))]
    paths = [os.path.abspath(p or os.getcwd()) for p in sys.path]
    return [
        p
        for p in dict.fromkeys(paths)
        if os.path.exists(p)
        and (not any(same_folder(p, u) for u in untrusted) or any(same_folder(p, str(n)) for n in needed))
    ]


def _child_env(request: dict[str, Any]) -> dict[str, str]:
    scratch = request["scratch"]
    return {
        "PATH": os.environ.get("PATH", os.defpath),
        "PYTHONPATH": os.pathsep.join(child_path(request["path"], request["module"])),
        "PYTHONHASHSEED": "0",
        "PYTHONDONTWRITEBYTECODE": "1",
        "HOME": scratch,
        **dict.fromkeys(("TMPDIR", "TEMP", "TMP"), scratch),  # the temporary folder: POSIX's name, Windows' two
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
            with open(os.path.join(path, "pids.max"), "w", encoding="ascii") as f:
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
