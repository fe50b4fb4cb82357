"""Helpers of the golden tests: drive inputs at exact times and record what the CPU did, scan by scan.

Times in the golden tests are seconds as the textbook gives them; inside they are integer nanoseconds
on the CPU's one clock. Recording never refreshes a timer (it reads what a watch table shows).

>>> ns(1.5)
1500000000
>>> held("TL", (1, 6))
[(1, 'TL', True), (6, 'TL', False)]
"""

from __future__ import annotations

from collections.abc import Callable, Iterable
from typing import Any

from plcsim import CPU

Event = tuple[float, str, Any]


def ns(seconds: float) -> int:
    """Seconds (as the textbook writes them) to integer nanoseconds."""
    return round(seconds * 1_000_000_000)


def held(name: str, *intervals: tuple[float, float]) -> list[Event]:
    """Input ``name`` TRUE during each ``(on, off)`` interval (seconds), FALSE otherwise."""
    events: list[Event] = []
    for on, off in intervals:
        events += [(on, name, True), (off, name, False)]
    return events


def drive(cpu: CPU, events: Iterable[Event], until: float) -> None:
    """Apply input events at their times (those up to ``until``) and run to ``until`` seconds.

    An input set at time T is seen by the task that starts at T (``run_until`` runs events strictly
    before T, then the input changes).
    """
    for when, name, value in sorted(events, key=lambda e: e[0]):
        if when > until:
            break
        cpu.run_until(ns(when))
        cpu.set_input(name, value)
    cpu.run_until(ns(until))


class Probe:
    """Record the values of tags after every OB1 scan, stamped with the scan's start time.

    ``names`` are anything :meth:`CPU.read` takes (``"LED"``, ``"TON_1.ET"``, ``"D.CISLO"``, ``"%MW10"``);
    ``outputs=True`` records the physical outputs (``cpu.outputs``) instead, stamped with the scan's end,
    when the output modules receive them.
    """

    def __init__(self, cpu: CPU, *names: str, outputs: bool = False):
        self.cpu, self.names, self.outputs = cpu, names, outputs
        self.samples: dict[str, list[tuple[int, Any]]] = {n: [] for n in names}
        cpu.on_scan_end = self._record

    def _record(self, cpu: CPU) -> None:
        stamp = cpu.scan_end_ns if self.outputs else cpu.scan_start_ns
        for name in self.names:
            value = cpu.outputs[name] if self.outputs else cpu.read(name)
            self.samples[name].append((stamp, value))

    def changes(self, name: str) -> list[tuple[float, Any]]:
        """``(seconds, value)`` for the first scan and for every scan whose value differs from the previous one."""
        out: list[tuple[float, Any]] = []
        for stamp, value in self.samples[name]:
            if not out or out[-1][1] != value:
                out.append((stamp / 1e9, value))
        return out

    def rises(self, name: str) -> list[int]:
        """Scan start times (ns) of the scans in which a Bool became TRUE."""
        prev, out = False, []
        for stamp, value in self.samples[name]:
            if value and not prev:
                out.append(stamp)
            prev = value
        return out

    def true_runs(self, name: str) -> list[int]:
        """How many consecutive scans each TRUE stretch of a Bool lasted."""
        runs: list[int] = []
        prev = False
        for _, value in self.samples[name]:
            if value:
                if prev:
                    runs[-1] += 1
                else:
                    runs.append(1)
            prev = value
        return runs

    def at(self, name: str, seconds: float) -> Any:
        """The value recorded by the scan that started at ``seconds``."""
        stamp = ns(seconds)
        for when, value in self.samples[name]:
            if when == stamp:
                return value
        raise KeyError(f"no scan started at {seconds} s")


def sample(
    cpu: CPU, events: Iterable[Event], until: float, read: Callable[[CPU], Any], step: float = 0.001
) -> list[tuple[float, Any]]:
    """Observe ``read(cpu)`` on a time grid, independent of OB1: ``(seconds, value)`` at every change.

    At each grid time T: run every event before T, apply the inputs due at T, run the events at T
    (task starts and their networks, an OB30 call due at T), then read. A change made at T is
    therefore reported at T; an output written at the end of an execution is reported at that end.
    Input events must lie on the grid.
    """
    pending = sorted(events, key=lambda e: e[0])
    grid = ns(step)
    out: list[tuple[float, Any]] = []
    k = 0
    for tick in range(ns(until) // grid + 1):
        now = tick * grid
        cpu.run_until(now)
        while k < len(pending) and ns(pending[k][0]) <= now:
            if ns(pending[k][0]) != now:
                raise ValueError(f"event {pending[k]} is not on the {step} s grid")
            cpu.set_input(pending[k][1], pending[k][2])
            k += 1
        cpu.run_until(now + 1)
        value = read(cpu)
        if not out or out[-1][1] != value:
            out.append((now / 1e9, value))
    return out
