"""What the Tecomat exercises T-01..T-05 share: their programs' folder, the manual's press patterns and
the truths their checks compare a program with (products counted since the last reset, the time switch's
schedule on the real-time clock).

The exercises are examples of the Tecomat manual (``spec/tecomat.md`` §7) on the course's rigs; their
programs are ``.il`` files under ``exercises/solutions/T_NN/``. The I/O tables give S7 addresses
(``%I0.0``), which the Tecomat front end reads as the scratchpad's X0.0 (``%Q`` -> Y, ``%M`` -> R).
"""

from __future__ import annotations

import datetime as dt
from dataclasses import dataclass
from typing import Any

import numpy as np

from exercises._common import solution
from plcsim.check import Condition, Context
from plcsim.exercise import Solution
from plcsim.scenario import press


def il_solution(number: str, name: str, *args: Any, **kwargs: Any) -> Solution:
    """A shipped Tecomat program: ``exercises/solutions/T_01/<name>.il`` for exercise ``T-01`` (the arguments
    of :func:`exercises._common.solution`)."""
    return solution(number, name, *args, suffix=".il", **kwargs)


def start_stop(start: str, stop: str, cycles: int) -> list:
    """START and STOP pressed in turn (2..150 ms) at seeded times; every other cycle presses a button twice
    (START while running, STOP while stopped)."""
    actions: list = []
    t = 200
    for k in range(cycles):
        for button in (start, stop):
            for _ in range(2 if k % 2 else 1):
                actions += press(button, t=f"{t}ms..{t + 80}ms", hold="2ms..150ms")
                t += 300
    return actions


def both_pressed(start: str, stop: str) -> list:
    """The overlaps: START held and STOP pressed inside it; STOP held and START pressed inside it (and still
    held after it); both pressed in the same instant, STOP released first."""
    return [
        *press(start, t="200ms..300ms", hold="1.2s..1.4s"),
        *press(stop, t="600ms..700ms", hold="300ms..500ms"),
        *press(stop, t="2s..2.1s", hold="600ms..800ms"),
        *press(start, t="2.3s..2.4s", hold="900ms..1.1s"),
        *press(stop, t="3.8s..3.9s", hold="50ms..150ms"),
        *press(start, t="4.2s", hold="300ms..400ms"),
        *press(stop, t="4.2s", hold="100ms..200ms"),
    ]


@dataclass(frozen=True)
class CountedSinceReset(Condition):
    """``counter`` equals, in every cycle, the rising edges of ``pulse`` since ``reset`` was last seen (the
    counter is 0 while ``reset`` is on, and an edge in a cycle that sees ``reset`` is not counted: a counter's
    reset dominates, EX-15), as the controller's input image saw them."""

    counter: str
    pulse: str
    reset: str

    def truth(self, ctx: Context) -> np.ndarray:
        pulse = ctx.trace.column(self.pulse).astype(bool)
        reset = ctx.trace.column(self.reset).astype(bool)
        rises = pulse & ~np.concatenate(([False], pulse[:-1]))
        out = np.zeros(len(pulse), dtype=np.int64)
        n = 0
        for k in range(len(pulse)):
            n = 0 if reset[k] else n + int(rises[k])
            out[k] = n
        return out

    def rows(self, ctx: Context) -> np.ndarray:
        return ctx.trace.column(self.counter).astype(np.int64) == self.truth(ctx)

    def describe(self) -> str:
        return f"{self.counter} == rising edges of {self.pulse} since {self.reset}"

    def signals(self) -> list[str]:
        return [self.counter, self.pulse, self.reset]


def _minutes(hhmm: int) -> int:
    """``$0A1E`` (hour in the high byte, minute in the low one, as SW7 holds them) -> 630."""
    return (hhmm >> 8) * 60 + (hhmm & 0xFF)


@dataclass(frozen=True)
class OnSchedule(Condition):
    """The real-time clock that a cycle saw at its start is inside one of the ``[on, off)`` minutes windows
    (``$800`` = 08:00 as SW7 holds it). The clock is the trace's ``rtc_start`` advanced by the cycle's start
    time, or the last ``set_clock`` of the scenario before it advanced since then."""

    on: tuple[int, ...]
    off: tuple[int, ...]

    def minutes(self, ctx: Context) -> np.ndarray:
        """The clock's minute of the day at each cycle's start."""
        starts = ctx.trace.times
        base_ns, base = 0, _clock(str(ctx.trace.meta.get("rtc_start") or "00:00:00"))
        out = np.empty(len(starts), dtype=np.int64)
        sets = sorted((e.t_ns, _clock(e.subject)) for e in ctx.trace.events_of("set_clock", None, "scenario"))
        k = 0
        for i, t in enumerate(starts):
            while k < len(sets) and sets[k][0] <= t:
                base_ns, base = sets[k]
                k += 1
            out[i] = int((base + (int(t) - base_ns) // 1_000_000_000) // 60 % 1440)
        return out

    def rows(self, ctx: Context) -> np.ndarray:
        m = self.minutes(ctx)
        inside = np.zeros(len(m), dtype=bool)
        for on, off in zip(self.on, self.off, strict=True):
            inside |= (m >= _minutes(on)) & (m < _minutes(off))
        return inside

    def describe(self) -> str:
        windows = ", ".join(f"{_hhmm(a)}-{_hhmm(b)}" for a, b in zip(self.on, self.off, strict=True))
        return f"the clock in {windows}"

    def signals(self) -> list[str]:
        return []


def _hhmm(value: int) -> str:
    return f"{value >> 8:02d}:{value & 0xFF:02d}"


def _clock(text: str) -> int:
    """Seconds of the day of ``"07:59:30"``, ``"2024-07-01-07:59:30"`` or ``"DTL#2024-07-01-07:59:30"``."""
    moment = dt.time.fromisoformat(text.rpartition("-")[2])
    return moment.hour * 3600 + moment.minute * 60 + moment.second
