"""Confinement of the grading child, applied by the child to itself before it loads a submission.

Each guard is independent, so that one the OS lacks does not remove the others; each reports
whether it is in force (the grader lists the missing ones in the report's warnings):

* resource limits (POSIX ``resource``): CPU seconds, address space, file size, no core files and,
  for an unprivileged user, no new process or thread (``RLIMIT_NPROC`` = 1). Root ignores
  ``RLIMIT_NPROC`` (and could raise the others), so for root a ``pids`` cgroup with ``pids.max`` = 1
  is the process-count guard, where the cgroup file system is writable;
* namespaces (Linux ``unshare``): a new PID namespace, so that every process the child starts dies
  with it, and a new network namespace (no interface but a down loopback); an unprivileged user gets
  them inside a new user namespace;
* Landlock (Linux 5.13+): no file may be read but those the grader lists (the Python installation,
  the packages; not the exercise's solutions, not the other submissions, not the other children's
  scratch folders), none created, written, truncated or removed outside the scratch folder; no TCP
  bind or connect (ABI 4), no signal to a process outside (ABI 6).

macOS has the resource limits but does not enforce the address-space one, and no namespaces or
Landlock; Windows has none of these. On the portable path (Windows, or ``PLCSIM_SANDBOX=portable``)
the child applies nothing but :func:`exit_with_grader`, and the grader enforces the limits from
outside (:mod:`plcsim.grading.sandbox.watchdog`); its report lists what is missing.
"""

from __future__ import annotations

import ctypes
import ctypes.util
import os
import sys
import threading
from typing import Any

CLONE_NEWNS = 0x00020000
CLONE_NEWUSER = 0x10000000
CLONE_NEWPID = 0x20000000
CLONE_NEWNET = 0x40000000
PR_SET_NO_NEW_PRIVS = 38
PR_SET_PDEATHSIG = 1

_SYS = {"x86_64": (444, 445, 446), "aarch64": (444, 445, 446)}
"""Landlock system call numbers: create_ruleset, add_rule, restrict_self (the same on both)."""

_FS_WRITE_ABI1 = sum(1 << k for k in (1, 4, 5, 6, 7, 8, 9, 10, 11, 12))
"""WRITE_FILE, REMOVE_DIR, REMOVE_FILE, MAKE_CHAR, MAKE_DIR, MAKE_REG, MAKE_SOCK, MAKE_FIFO, MAKE_BLOCK, MAKE_SYM."""
_FS_REFER, _FS_TRUNCATE, _FS_IOCTL_DEV = 1 << 13, 1 << 14, 1 << 15
_FS_READ = (1 << 0) | (1 << 2) | (1 << 3)
"""EXECUTE, READ_FILE, READ_DIR."""
_FS_FILE_RIGHTS = (1 << 0) | (1 << 1) | (1 << 2) | _FS_TRUNCATE | _FS_IOCTL_DEV
"""The rights a rule on a file (not a folder) may carry: EXECUTE, WRITE_FILE, READ_FILE, TRUNCATE, IOCTL_DEV."""
_NET_BIND_TCP, _NET_CONNECT_TCP = 1, 2
_SCOPE_ABSTRACT_UNIX_SOCKET, _SCOPE_SIGNAL = 1, 2


def _libc() -> Any:
    return ctypes.CDLL(ctypes.util.find_library("c") or None, use_errno=True)


def available() -> bool:
    """True on systems with POSIX resource limits (Linux, the BSDs); False on Windows."""
    try:
        import resource  # noqa: F401 - only its presence matters
    except ImportError:
        return False
    return True


def set_limits(cpu_seconds: int, memory_mb: int, file_mb: int = 64) -> list[str]:
    """Set hard and soft limits the child cannot raise (unless it is root); returns what is missing."""
    try:
        import resource
    except ImportError:
        return ["no resource limits on this system (Windows): the grader watches the limits from outside"]
    missing = []
    wanted = [
        ("RLIMIT_CPU", (cpu_seconds, cpu_seconds + 1)),  # SIGXCPU at the soft limit, SIGKILL a second later
        ("RLIMIT_AS", (memory_mb << 20, memory_mb << 20)),
        ("RLIMIT_FSIZE", (file_mb << 20, file_mb << 20)),
        ("RLIMIT_CORE", (0, 0)),
    ]
    for name, value in wanted:
        try:
            resource.setrlimit(getattr(resource, name), value)
        except (AttributeError, ValueError, OSError):
            missing.append(f"{name} could not be set")
    return missing


def forbid_processes(cgroup: str | None) -> list[str]:
    """No new process or thread from now on: RLIMIT_NPROC = 1, and for root the ``pids`` cgroup."""
    missing = []
    try:
        import resource

        resource.setrlimit(resource.RLIMIT_NPROC, (1, 1))
    except (ImportError, AttributeError, ValueError, OSError):
        missing.append("RLIMIT_NPROC could not be set")
    if hasattr(os, "geteuid") and os.geteuid() == 0:
        try:
            if cgroup is None:
                raise OSError("no pids cgroup")
            with open(os.path.join(cgroup, "cgroup.procs"), "w", encoding="ascii") as f:
                f.write(str(os.getpid()))
        except OSError:
            missing.append("running as root without a writable pids cgroup: the process count is not limited")
    return missing


def enter_namespaces() -> tuple[bool, list[str]]:
    """New PID and network namespaces (in a new user namespace if not root): whether the PID namespace
    is in force, and what is missing.

    The PID namespace applies to the children of this process: the caller forks once, and the child
    is process 1 of the namespace; when it ends, the kernel kills every process left in it."""
    if not sys.platform.startswith("linux"):
        return False, ["no Linux namespaces: a process the submission starts is only killed with its group"]
    libc = _libc()
    flags = CLONE_NEWPID | CLONE_NEWNET | (CLONE_NEWUSER if os.geteuid() != 0 else 0)
    if libc.unshare(flags) == 0:
        return True, []
    if libc.unshare(flags & ~CLONE_NEWNET) == 0:
        return True, ["no network namespace: the network is only closed by Landlock (TCP)"]
    return False, ["no PID or network namespace: a process the submission starts is only killed with its group"]


ORPHANED_EXIT = 87
"""Exit code of a portable child whose grader ended."""


def exit_with_grader() -> None:
    """Portable (any OS): end this process once the grader's end of stdin closes, i.e. the grader ended.

    The grader holds the write end of the child's stdin and never writes to it; a read returns
    end-of-file only when every write end is closed. The thread reads the raw descriptor: blocked in
    ``sys.stdin.buffer.read()`` it would hold the buffer's lock, and the interpreter, ending, would
    abort on it."""

    def wait_for_end_of_input() -> None:
        try:
            while os.read(0, 4096):
                pass
        except OSError:  # no stdin at all: nothing to wait for
            return
        os._exit(ORPHANED_EXIT)

    threading.Thread(target=wait_for_end_of_input, name="plcsim-grader-watch", daemon=True).start()


def die_with_parent() -> None:
    """Ask the kernel to kill this process when its parent ends (Linux)."""
    if sys.platform.startswith("linux"):
        import signal

        _libc().prctl(PR_SET_PDEATHSIG, signal.SIGKILL, 0, 0, 0)


class _RulesetAttr(ctypes.Structure):
    _fields_ = [
        ("handled_access_fs", ctypes.c_uint64),
        ("handled_access_net", ctypes.c_uint64),
        ("scoped", ctypes.c_uint64),
    ]


class _PathBeneath(ctypes.Structure):
    _pack_ = 1
    _fields_ = [("allowed_access", ctypes.c_uint64), ("parent_fd", ctypes.c_int32)]


def restrict_files(scratch: str, readable: list[str]) -> list[str]:
    """Landlock: read only ``readable`` (files or folders), write only below ``scratch``, no TCP, no
    signal outside; returns what is missing."""
    numbers = _SYS.get(os.uname().machine) if hasattr(os, "uname") else None
    if not sys.platform.startswith("linux") or numbers is None:
        return ["no Landlock: the submission may read and write wherever the grading user may"]
    create, add_rule, restrict = numbers
    libc = _libc()
    libc.syscall.restype = ctypes.c_long
    abi = libc.syscall(create, None, ctypes.c_size_t(0), ctypes.c_uint32(1))  # LANDLOCK_CREATE_RULESET_VERSION
    if abi < 1:
        return ["no Landlock in this kernel: the submission may read and write wherever the grading user may"]
    write = _FS_WRITE_ABI1 | (_FS_REFER if abi >= 2 else 0) | (_FS_TRUNCATE if abi >= 3 else 0)
    write |= _FS_IOCTL_DEV if abi >= 5 else 0
    attr = _RulesetAttr(write | _FS_READ, _NET_BIND_TCP | _NET_CONNECT_TCP if abi >= 4 else 0, 0)
    if abi >= 6:
        attr.scoped = _SCOPE_ABSTRACT_UNIX_SOCKET | _SCOPE_SIGNAL
    size = 24 if abi >= 6 else 16 if abi >= 4 else 8
    ruleset = libc.syscall(create, ctypes.byref(attr), ctypes.c_size_t(size), ctypes.c_uint32(0))
    if ruleset < 0:
        return [f"Landlock refused the rules (errno {ctypes.get_errno()}): files are not confined"]
    try:
        missing = [] if _allow(libc, add_rule, ruleset, scratch, write | _FS_READ) else ["scratch folder refused"]
        for path in readable:
            _allow(libc, add_rule, ruleset, path, _FS_READ)
        libc.prctl(PR_SET_NO_NEW_PRIVS, 1, 0, 0, 0)
        if missing or libc.syscall(restrict, ruleset, ctypes.c_uint32(0)) != 0:
            return [f"Landlock could not be applied (errno {ctypes.get_errno()}): files are not confined"]
    finally:
        os.close(ruleset)
    return [] if abi >= 4 else ["Landlock ABI < 4: TCP is not blocked"]


def _allow(libc: Any, add_rule: int, ruleset: int, path: str, access: int) -> bool:
    """Add a path-beneath rule; a file gets only the rights a file can have."""
    try:
        where = os.open(path, os.O_PATH | os.O_CLOEXEC)
    except OSError:
        return False
    try:
        if not os.path.isdir(path):
            access &= _FS_FILE_RIGHTS
        rule = _PathBeneath(access, where)
        return libc.syscall(add_rule, ruleset, 1, ctypes.byref(rule), ctypes.c_uint32(0)) == 0
    finally:
        os.close(where)
