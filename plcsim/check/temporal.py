"""Statements over time: never, always, holds ... until, eventually."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from plcsim.check.base import (
    Check,
    Context,
    Names,
    Span,
    Verdict,
    first_bad_row,
    names_of,
    row_values,
    signals_of,
    window_ns,
)
from plcsim.check.conditions import Condition, as_condition
from plcsim.check.occurrences import EventOccurrences, Occurrences, occurrence_or_condition


@dataclass
class Never(Check):
    what: Condition | Occurrences
    tolerance: Span | None = None
    window: tuple[Span, Span] | None = None
    name: str | None = None
    weight: float = 1.0

    def for_more_than(self, span: str | int) -> Never:
        """Allow the condition for up to ``span`` at a time (a reaction time)."""
        self.tolerance = Span.parse(span)
        return self

    def during(self, start: str | int, end: str | int) -> Never:
        """Only look at ``start``..``end`` of the run."""
        self.window = (Span.parse(start), Span.parse(end))
        return self

    def names(self) -> Names:
        return names_of(self.what) + super().names()

    def describe(self) -> str:
        text = f"never {self.what.describe()}"
        if self.tolerance is not None:
            text += f" for more than {self.tolerance}"
        return text

    def evaluate(self, ctx: Context) -> Verdict:
        signals = self.what.signals()
        if isinstance(self.what, Occurrences):
            times = self.what.times(ctx)
            w = window_ns(ctx, self.window)
            if w is not None:
                times = times[(times >= w[0]) & (times < w[1])]
            if len(times):
                subject = ""
                if isinstance(self.what, EventOccurrences):
                    evs = [e for e in ctx.trace.events if e.t_ns == times[0] and e.kind == self.what.kind]
                    if evs:
                        subject = f" ({evs[0].subject}{', ' + evs[0].part if evs[0].part else ''})"
                return Verdict(
                    False,
                    f"expected never {self.what.describe()}; it happened {len(times)} time(s), "
                    f"first at {ctx.t(times[0])}{subject}",
                    int(times[0]),
                    signals,
                    (int(times[0]), int(times[0])),
                )
            return Verdict(True, "it never happened", None, signals)
        k = first_bad_row(ctx, self.what.rows(ctx), window_ns(ctx, self.window), self.tolerance)
        if k is None:
            return Verdict(True, "it never held", None, signals)
        t0 = int(ctx.trace.times[k])
        return Verdict(
            False,
            f"expected never {self.what.describe()}; it held in the scan at {ctx.t(t0)} "
            f"({row_values(ctx, k, signals)})",
            t0,
            signals,
            (t0, int(ctx.trace.end_times[k])),
        )


def never(what: str | Condition | Occurrences) -> Never:
    """The condition holds in no scan, or the event never happens."""
    return Never(occurrence_or_condition(what))


@dataclass
class Always(Check):
    condition: Condition
    window: tuple[Span, Span] | None = None
    tolerance: Span | None = None
    name: str | None = None
    weight: float = 1.0

    def during(self, start: str | int, end: str | int) -> Always:
        """Only look at ``start``..``end`` of the run."""
        self.window = (Span.parse(start), Span.parse(end))
        return self

    def except_for(self, span: str | int) -> Always:
        """Allow the condition to fail for up to ``span`` at a time."""
        self.tolerance = Span.parse(span)
        return self

    def names(self) -> Names:
        return names_of(self.condition) + super().names()

    def describe(self) -> str:
        return f"always {self.condition.describe()}"

    def evaluate(self, ctx: Context) -> Verdict:
        signals = self.condition.signals()
        k = first_bad_row(ctx, ~self.condition.rows(ctx), window_ns(ctx, self.window), self.tolerance)
        if k is None:
            return Verdict(True, "it held in every scan", None, signals)
        t0 = int(ctx.trace.times[k])
        return Verdict(
            False,
            f"expected always {self.condition.describe()}; it failed in the scan at {ctx.t(t0)} "
            f"({row_values(ctx, k, signals)})",
            t0,
            signals,
            (t0, int(ctx.trace.end_times[k])),
        )


def always(condition: str | Condition) -> Always:
    """The condition holds in every scan."""
    return Always(as_condition(condition))


@dataclass
class HoldsBuilder:
    condition: Condition

    def until(self, release: Occurrences) -> Holds:
        """Once true, the condition stays true until ``release`` happens (or the run ends)."""
        return Holds(self.condition, release, None)

    def to_the_end(self) -> Holds:
        """Once true, the condition stays true until the run ends (a latch nothing in the scenario resets)."""
        return Holds(self.condition, None, None)

    def for_at_least(self, span: str | int) -> Holds:
        """Each time the condition becomes true it stays true at least ``span``."""
        return Holds(self.condition, None, Span.parse(span))


@dataclass
class Holds(Check):
    condition: Condition
    release: Occurrences | None
    minimum: Span | None
    name: str | None = None
    weight: float = 1.0

    def names(self) -> Names:
        return names_of(self.condition, self.release) + super().names()

    def describe(self) -> str:
        if self.release is not None:
            return f"{self.condition.describe()} holds until {self.release.describe()}"
        if self.minimum is None:
            return f"{self.condition.describe()} holds to the end of the run"
        return f"{self.condition.describe()} holds for at least {self.minimum}"

    def evaluate(self, ctx: Context) -> Verdict:
        rows = self.condition.rows(ctx)
        times, ends = ctx.trace.times, ctx.trace.end_times
        signals = signals_of(self.condition, self.release)
        starts = np.nonzero(rows & ~np.concatenate(([False], rows[:-1])))[0]
        if len(starts) == 0:
            return Verdict(
                False, f"expected {self.condition.describe()} to hold at some point; it never did", None, signals
            )
        releases = self.release.times(ctx) if self.release is not None else np.zeros(0, dtype=np.int64)
        for k in starts:
            j = k
            while j + 1 < len(rows) and rows[j + 1]:
                j += 1
            fell_at = int(times[j + 1]) if j + 1 < len(rows) else None
            began = int(times[k])
            if self.release is not None:
                if fell_at is None:
                    continue
                released = releases[(releases > began) & (releases <= fell_at)]
                if len(released) == 0:
                    return Verdict(
                        False,
                        f"expected {self.condition.describe()} to hold until "
                        f"{self.release.describe()}; it became true at {ctx.t(began)} and stopped "
                        f"at {ctx.t(fell_at)} without it",
                        fell_at,
                        signals,
                        (began, fell_at),
                    )
            elif self.minimum is None:
                if fell_at is not None:
                    return Verdict(
                        False,
                        f"expected {self.condition.describe()} to hold to the end of the run; it became true at "
                        f"{ctx.t(began)} and stopped at {ctx.t(fell_at)}",
                        fell_at,
                        signals,
                        (began, fell_at),
                    )
            else:
                length = int(ends[j]) - began
                if fell_at is not None and length < self.minimum.resolve(ctx.scan_ns):  # type: ignore[union-attr]
                    return Verdict(
                        False,
                        f"expected {self.condition.describe()} to hold at least {self.minimum}; "
                        f"from {ctx.t(began)} it held only {ctx.t(length)}",
                        began,
                        signals,
                        (began, int(ends[j])),
                    )
        return Verdict(True, f"it held as required ({len(starts)} time(s))", None, signals)


def holds(condition: str | Condition) -> HoldsBuilder:
    """Start a statement about how long a condition stays true."""
    return HoldsBuilder(as_condition(condition))


@dataclass
class Eventually(Check):
    what: Condition | Occurrences
    deadline: Span | None = None
    name: str | None = None
    weight: float = 1.0

    def before(self, deadline: str | int) -> Eventually:
        """It must happen before this time of the run."""
        self.deadline = Span.parse(deadline)
        return self

    def names(self) -> Names:
        return names_of(self.what) + super().names()

    def describe(self) -> str:
        return f"eventually {self.what.describe()}" + (f" before {self.deadline}" if self.deadline else "")

    def evaluate(self, ctx: Context) -> Verdict:
        limit = self.deadline.resolve(ctx.scan_ns) if self.deadline else ctx.end_ns + 1
        signals = self.what.signals()
        if isinstance(self.what, Occurrences):
            times = self.what.times(ctx)
        else:
            rows = self.what.rows(ctx)
            times = ctx.trace.times[rows]
        hits = times[times < limit]
        if len(hits):
            return Verdict(True, f"first at {ctx.t(hits[0])}", int(hits[0]), signals)
        later = f"; it first happened at {ctx.t(times[0])}" if len(times) else "; it never happened"
        return Verdict(
            False, f"expected {self.what.describe()} before {ctx.t(limit)}{later}", None, signals, (0, int(limit))
        )


def eventually(what: str | Condition | Occurrences) -> Eventually:
    """The condition holds in some scan (or the event happens)."""
    return Eventually(occurrence_or_condition(what))
