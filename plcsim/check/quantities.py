"""Numbers computed from the run, checked against bounds: counts, spacings, durations, duty, values."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from itertools import pairwise
from typing import Any

from plcsim.check.base import Check, Context, Names, Span, Verdict, names_of, show_number
from plcsim.check.conditions import Condition, as_condition
from plcsim.check.occurrences import Occurrences, becomes, event
from plcsim.trace.facade import Trace


@dataclass
class Quantity(Check):
    """A number computed from the run, checked against bounds."""

    label: str
    compute: Callable[[Context], tuple[float | None, list[int]]]
    sources: list[str]
    lo: float | None = None
    hi: float | None = None
    unit: str = ""
    every: bool = False
    name: str | None = None
    weight: float = 1.0
    measured: tuple[Any, ...] = ()  # the occurrences or condition it measures, for names()

    def names(self) -> Names:
        return Names(tuple(self.sources)) + names_of(*self.measured) + super().names()

    def equals(self, expected: float | str) -> Quantity:
        """Exactly this value (a duration literal is allowed for times)."""
        return self.between(expected, expected)

    def between(self, lo: float | str, hi: float | str) -> Quantity:
        """Within ``lo``..``hi`` inclusive (duration literals allowed, resolved with the scan time)."""
        self.lo, self.hi = lo, hi  # type: ignore[assignment]
        return self

    def at_least(self, lo: float | str) -> Quantity:
        self.lo = lo  # type: ignore[assignment]
        return self

    def at_most(self, hi: float | str) -> Quantity:
        self.hi = hi  # type: ignore[assignment]
        return self

    def _bound(self, value: Any, ctx: Context) -> float | None:
        if value is None:
            return None
        if isinstance(value, str):
            return float(Span.parse(value).resolve(ctx.scan_ns))
        return float(value)

    def _show(self, v: float, ctx: Context) -> str:
        return ctx.t(v) if self.unit == "ns" else show_number(v)

    def describe(self) -> str:
        return f"{'every ' if self.every else ''}{self.label}{self._bounds_text(self.lo, self.hi)}"

    @staticmethod
    def _bounds_text(lo: Any, hi: Any) -> str:
        if lo is not None and lo == hi:
            return f" = {lo}"
        if lo is not None and hi is not None:
            return f" between {lo} and {hi}"
        if lo is not None:
            return f" at least {lo}"
        if hi is not None:
            return f" at most {hi}"
        return ""

    def evaluate(self, ctx: Context) -> Verdict:
        lo, hi = self._bound(self.lo, ctx), self._bound(self.hi, ctx)
        result = self.compute(ctx)
        values, at = result
        items = values if isinstance(values, list) else [values]
        if not items or items == [None]:
            message = f"expected {self.describe()}; there was nothing to measure"
            return Verdict(False, message, None, self.sources, nothing_to_check=True)
        for k, v in enumerate(items):
            if v is None or (lo is not None and v < lo) or (hi is not None and v > hi):
                when = at[k] if k < len(at) else None
                where = f" (at {ctx.t(when)})" if when is not None else ""
                shown = "nothing" if v is None else self._show(v, ctx)
                bounds = self._bounds_text(
                    None if lo is None else self._show(lo, ctx), None if hi is None else self._show(hi, ctx)
                )
                return Verdict(
                    False,
                    f"expected {'every ' if self.every else ''}{self.label}{bounds}; measured {shown}{where}",
                    when,
                    self.sources,
                    (when, when + (int(v) if self.unit == "ns" and v else 0)) if when is not None else None,
                )
        shown = ", ".join(self._show(v, ctx) for v in items[:5]) + (" ..." if len(items) > 5 else "")
        return Verdict(True, f"measured {shown}", None, self.sources)


def count(what: Occurrences | str | Condition) -> Quantity:
    """How many times something happened: ``count(rises("Takt1s")).between(59, 61)``."""
    occ = what if isinstance(what, Occurrences) else becomes(what)

    def compute(ctx: Context) -> tuple[float, list[int]]:
        return float(len(occ.times(ctx))), []

    return Quantity(f"number of times {occ.describe()}", compute, occ.signals(), measured=(occ,))


def spacing(what: Occurrences) -> Quantity:
    """Every time between two successive occurrences: ``spacing(rises("Takt1s")).between("1s", "1s + 1 scan")``."""

    def compute(ctx: Context) -> tuple[list[float], list[int]]:
        times = what.times(ctx)
        return [float(b - a) for a, b in pairwise(times)], [int(t) for t in times[:-1]]

    q = Quantity(f"time between successive '{what.describe()}'", compute, what.signals(), unit="ns", measured=(what,))
    q.every = True
    return q


def durations(condition: str | Condition, *, include_last: bool = False) -> Quantity:
    """Every length of time the condition stayed true (the unfinished last one is left out)."""
    cond = as_condition(condition)

    def compute(ctx: Context) -> tuple[list[float], list[int]]:
        rows = cond.rows(ctx)
        times, ends = ctx.trace.times, ctx.trace.end_times
        out, at = [], []
        k, n = 0, len(rows)
        while k < n:
            if rows[k]:
                j = k
                while j + 1 < n and rows[j + 1]:
                    j += 1
                if j + 1 < n or include_last:
                    out.append(float(ends[j] - times[k]))
                    at.append(int(times[k]))
                k = j + 1
            else:
                k += 1
        return out, at

    q = Quantity(f"time {cond.describe()} stays true", compute, cond.signals(), unit="ns", measured=(cond,))
    q.every = True
    return q


def duty(condition: str | Condition, *, start: str | int = 0, end: str | int | None = None) -> Quantity:
    """The fraction of time the condition is true, between ``start`` and ``end`` of the run."""
    cond = as_condition(condition)

    def compute(ctx: Context) -> tuple[float | None, list[int]]:
        rows = cond.rows(ctx)
        times, ends = ctx.trace.times, ctx.trace.end_times
        t0 = Span.parse(start).resolve(ctx.scan_ns)
        t1 = Span.parse(end).resolve(ctx.scan_ns) if end is not None else ctx.end_ns
        sel = (times >= t0) & (ends <= t1)
        total = float((ends[sel] - times[sel]).sum())
        if total <= 0:
            return None, []
        return float((ends[sel & rows] - times[sel & rows]).sum()) / total, []

    return Quantity(f"fraction of time {cond.describe()}", compute, cond.signals(), measured=(cond,))


def final(name: str) -> Quantity:
    """The value of a tag at the end of the run: ``final("MOTOR.SEKUNDY").equals(15)``."""

    def compute(ctx: Context) -> tuple[float | None, list[int]]:
        col = ctx.trace.column(name)
        if len(col) == 0:
            return None, []
        return float(col[-1]), [int(ctx.trace.times[-1])]

    return Quantity(f"{name} at the end", compute, [name])


def measure(
    label: str, compute: Callable[[Trace], float | list[float | None] | None], *signals: str, unit: str = ""
) -> Quantity:
    """A number an instructor computes from the trace with Python: the escape hatch of the language.

    ``compute(trace)`` returns a number (or a list of numbers, each checked); ``signals`` are plotted
    when the check fails. Example: the hours meter counts the seconds the belt ran::

        measure("SEKUNDY minus seconds with D1 on", lambda tr: ..., "MOTOR.SEKUNDY", "D1").between(-1, 1)
    """

    def run(ctx: Context) -> tuple[Any, list[int]]:
        value = compute(ctx.trace)
        if isinstance(value, (list, tuple)):
            return [None if v is None else float(v) for v in value], []  # None: nothing to measure there, a failure
        return (None if value is None else float(value)), []

    q = Quantity(label, run, list(signals), unit=unit)
    return q


def event_data(kind: str, key: str, subject: str | None = None) -> Quantity:
    """Every value of ``key`` in the data of the plant events ``kind`` (about ``subject``): a plant's own
    measurement graded like any number, ``event_data("alignment measured", "gap_mm").at_most(1.0)``.

    No such event is a failure ("nothing to measure"), and so is an event without ``key``.
    """
    occ = event(kind, subject)

    def compute(ctx: Context) -> tuple[list[float | None], list[int]]:
        events = ctx.trace.events_of(kind, None, "plant")
        events = [e for e in events if subject is None or subject in (e.subject, e.part)]
        values = [e.data.get(key) for e in events]
        return [float(v) if isinstance(v, int | float) else None for v in values], [e.t_ns for e in events]

    q = Quantity(f"{key} of '{kind}'" + (f" {subject}" if subject else ""), compute, [], measured=(occ,))
    q.every = True
    return q


def value_at(name: str, when: str | int) -> Quantity:
    """The value of a tag at a time of the run."""

    def compute(ctx: Context) -> tuple[float | None, list[int]]:
        t = Span.parse(when).resolve(ctx.scan_ns)
        return float(ctx.trace.value_at(name, t)), [t]

    return Quantity(f"{name} at {when}", compute, [name])
