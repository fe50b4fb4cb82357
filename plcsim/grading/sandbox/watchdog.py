"""The grader's outside watch over a grading child, for systems where the child cannot limit itself.

Windows has no resource limits, process groups or namespaces a process can apply to itself, and
macOS accepts a limit on the address space but does not enforce it. There the grader polls the
child and every process it saw the child start (with psutil, every :data:`POLL_S` seconds) and
kills them all once they pass a limit: their CPU seconds together, their memory together (the
resident set or, on Windows, the private committed bytes, whichever is larger), or the size of the
result file. It is weaker than a limit the kernel enforces, and the sandbox's report says so:

* a limit is seen at the next poll, so a process may overshoot the memory limit by what it
  allocates in :data:`POLL_S` seconds (memory that is allocated but never written is not counted
  before it is written);
* the process table is scanned every :data:`SCAN_EVERY` polls: a process started and detached
  between two scans is not seen, and outlives the grade.
"""

from __future__ import annotations

import contextlib
import os
import sys
from dataclasses import dataclass, field
from typing import Any

POLL_S = 0.02
"""Seconds between two looks at the child's CPU time, memory and result file."""
SCAN_EVERY = 5
"""Polls between two scans of the process table for what the child started (a scan costs more)."""


@dataclass
class TreeWatch:
    """The child (``pid``) and the processes it started, measured against the limits asked for.

    ``cpu_seconds`` / ``memory_mb`` of None are not watched (the kernel enforces them); ``result_file``
    and ``max_bytes``, if given, bound the size of the file the child writes its result to."""

    pid: int
    cpu_seconds: float | None = None
    memory_mb: int | None = None
    result_file: str | None = None
    max_bytes: int | None = None
    cpu_s: float = 0.0
    """CPU seconds the watched processes used, as last measured (those that ended keep their last value)."""
    peak_mb: float = 0.0
    _seen: dict[int, Any] = field(default_factory=dict)
    _cpu: dict[int, float] = field(default_factory=dict)
    _polls: int = 0

    def __post_init__(self) -> None:
        import psutil

        with contextlib.suppress(psutil.Error):
            self._seen[self.pid] = psutil.Process(self.pid)

    def check(self) -> str | None:
        """Measure once: the limit passed (``cpu``, ``memory``, ``output``), or None."""
        import psutil

        if self._polls % SCAN_EVERY == 0:
            self._scan()
        self._polls += 1
        memory = 0
        for pid, process in list(self._seen.items()):
            try:
                with process.oneshot():
                    times = process.cpu_times()
                    memory += _footprint(process.memory_info())
                self._cpu[pid] = times.user + times.system
            except psutil.Error:  # it ended (its last CPU time stays counted) or is not ours to read
                continue
        self.cpu_s = sum(self._cpu.values())
        self.peak_mb = max(self.peak_mb, memory / (1 << 20))
        if self.cpu_seconds is not None and self.cpu_s >= self.cpu_seconds:
            return "cpu"
        if self.memory_mb is not None and memory > self.memory_mb << 20:
            return "memory"
        if self.result_file is not None and self.max_bytes is not None:
            with contextlib.suppress(OSError):
                if os.path.getsize(self.result_file) > self.max_bytes:
                    return "output"
        return None

    def kill_all(self) -> None:
        """Kill the child and every process seen (psutil refuses a PID that now names another process)."""
        import psutil

        self._scan()
        root = self._seen.get(self.pid)
        for process in [root, *(p for pid, p in self._seen.items() if pid != self.pid)]:
            if process is not None:
                with contextlib.suppress(psutil.Error):
                    process.kill()

    def _scan(self) -> None:
        import psutil

        root = self._seen.get(self.pid)
        if root is None:
            return
        with contextlib.suppress(psutil.Error):
            for child in root.children(recursive=True):
                self._seen.setdefault(child.pid, child)


def _footprint(info: Any) -> int:
    """Bytes a process holds: its resident set, or its private committed bytes (Windows) if larger."""
    return max(info.rss, getattr(info, "private", 0))


def outside_limits(portable: bool) -> tuple[bool, bool]:
    """Which limits the grader must watch from outside on this system: (CPU time, memory).

    >>> outside_limits(portable=True)
    (True, True)
    """
    if portable:
        return True, True
    return False, sys.platform == "darwin"  # macOS accepts RLIMIT_AS and does not enforce it
