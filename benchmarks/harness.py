"""Shared machinery of the benchmark groups: settings, the timed driver loop, and figure output.

The driver loop is inside the timing: applying the scheduled input changes costs the same for every
implementation and is part of what a co-simulation pays per scan. A run stops after its scan budget or
its wall-time budget, whichever comes first (the clock is checked every ``chunk`` scans), and reports
scans/s, so a time-bounded run is still comparable.
"""

from __future__ import annotations

import gc
import json
import statistics
import sys
import time
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

Figure = dict[str, Any]


@dataclass
class Settings:
    """Command-line settings shared by all groups, plus a cache for results one group lends another."""

    quick: bool = False
    repeats: int = 3
    seeds: tuple[int, ...] | None = None
    """Seeds for the groups that run every shipped solution (``--seeds``; None: the group's own)."""
    cache: dict[str, Any] = field(default_factory=dict)

    def size(self, full: int, quick: int) -> int:
        """The full size, or the tiny one under ``--quick``."""
        return quick if self.quick else full


def figure(name: str, value: Any, unit: str, **context: Any) -> Figure:
    """One output record; ``value`` None means the figure was skipped (say why in ``skipped``)."""
    return {"figure": name, "value": value, "unit": unit, **context}


def emit(fig: Figure) -> None:
    """Print one figure as one JSON line on stdout (the only thing that goes to stdout)."""
    print(json.dumps(fig), flush=True)


def progress(message: str) -> None:
    """Progress goes to stderr so stdout stays machine-readable."""
    print(message, file=sys.stderr, flush=True)


def drive(
    apply: Callable[[dict[str, Any]], Any],
    step: Callable[[], Any],
    sched: list[dict[str, Any] | None],
    n: int,
    max_s: float,
    chunk: int = 500,
) -> tuple[int, float]:
    """Run up to ``n`` scans (or ``max_s`` seconds): apply ``sched[k]`` then ``step()``. Returns (scans, s)."""
    perf = time.perf_counter
    t0 = perf()
    k = 0
    while k < n:
        end = min(k + chunk, n)
        while k < end:
            ch = sched[k]
            if ch:
                apply(ch)
            step()
            k += 1
        if perf() - t0 > max_s:
            break
    return k, perf() - t0


@dataclass
class Rates:
    """Scan rates of repeated runs."""

    rates: list[float]
    scans: list[int]

    @property
    def best(self) -> float:
        return max(self.rates)

    @property
    def median(self) -> float:
        return statistics.median(self.rates)

    @property
    def best_scans(self) -> int:
        return self.scans[self.rates.index(self.best)]


def measure(
    run_once: Callable[[int, float], tuple[int, float]], n: int, max_s: float, repeats: int, warmup: int = 1000
) -> Rates:
    """Warm up once (``warmup`` scans), then ``repeats`` full runs, each after a ``gc.collect()``."""
    run_once(min(n, warmup), max_s)
    rates, scans = [], []
    for _ in range(repeats):
        gc.collect()
        done, secs = run_once(n, max_s)
        rates.append(done / secs)
        scans.append(done)
    return Rates(rates, scans)
