"""The checker language: temporal statements over a trace, written the way an instructor thinks.

>>> conveyor_checks = [
...     rises("D1").within("1 scan").after(rises("S1")),
...     falls("D1").within("1 scan").after(rises("S2")),
...     never(all_of("D1", "S2")).named("belt stopped while a part is at S2"),
...     never(event("part fell off")),
... ]
>>> conveyor_checks[0].describe()
'D1 rises within 1 scan after S1 rises'

Building blocks:

* **occurrences** (points in time): ``rises("D1")``, ``falls("D1")``, ``event("part entered", "S2")``,
  ``action("press", "ACK")`` (a scenario action), ``becomes(condition)``, ``calls("OB30")`` (the
  starts of an interrupt task), ``either(a, b)``. An edge needs a scan before it: a signal already
  TRUE in the first scan has not risen (check it with ``eventually(...).before(...)``).
* **conditions** (true or false in each scan): a tag name (``"D1"`` means D1 is TRUE), ``off("D1")``,
  ``value("CISLO") > 0``, ``all_of(...)``, ``any_of(...)``, ``not_(...)``, ``implies(a, b)``,
  ``same("LED", "TLACIDLO")``.
* **checks**: ``X.within(d).after(Y)``, ``X.between(lo, hi).after(Y)``, ``never(c)``, ``always(c)``,
  ``holds(c).until(Y)``, ``holds(c).for_at_least(d)``, ``eventually(c).before(t)``, ``count(X)``,
  ``spacing(X)``, ``durations(c)``, ``duty(c)``, ``final("MOTOR.SEKUNDY")``, ``program_uses_no("SET")``,
  and ``measure(label, fn)`` for a number computed from the trace by a Python function.

Durations are literals with scans: ``"1 scan"``, ``"10s + 2 scans"``, ``"0.5s - 1 scan"`` (a scan is the
CPU's cycle time). Conditions are evaluated per scan on the values of that scan: an input as the
scan read it, an output as the scan wrote it, so ``always(implies("S2", off("D1")))`` says "in every
scan that saw S2, D1 was written FALSE", i.e. the reaction comes within one scan.
A failed check says what was expected, what happened and when, and names the signals to plot.
"""

from __future__ import annotations

import re
from collections.abc import Callable, Iterable, Sequence
from dataclasses import dataclass, field
from itertools import pairwise
from typing import Any

import numpy as np

from plcsim.errors import ConfigurationError
from plcsim.literals import duration_ns, format_ns
from plcsim.trace import Trace

# --------------------------------------------------------------------------------------------
# Durations with scans
# --------------------------------------------------------------------------------------------

_TERM = re.compile(r"\s*([+-]?)\s*(\d+(?:\.\d+)?)\s*(scans?|[a-z]+)\s*", re.IGNORECASE)


@dataclass(frozen=True)
class Span:
    """A duration written with time units and scans: ``"10s + 2 scans"``."""

    ns: int = 0
    scans: float = 0.0
    text: str = ""

    @classmethod
    def parse(cls, value: str | int | Span) -> Span:
        if isinstance(value, Span):
            return value
        if isinstance(value, int):
            return cls(value, 0, format_ns(value))
        if not isinstance(value, str):
            raise ConfigurationError(f"a duration is written like '10s', '1 scan' or '10s + 2 scans', not {value!r}")
        ns, scans, pos = 0, 0.0, 0
        text = value.strip()
        for m in _TERM.finditer(text):
            if m.start() != pos:
                break
            sign = -1 if m.group(1) == "-" else 1
            number, unit = m.group(2), m.group(3).lower()
            if unit.startswith("scan"):
                scans += sign * float(number)
            else:
                try:
                    ns += sign * duration_ns(number + unit)
                except Exception:  # noqa: BLE001 - any parse failure means a bad unit
                    raise ConfigurationError(
                        f"duration {value!r}: unknown unit {unit!r}; use s, ms, us, min, h or scans"
                    ) from None
            pos = m.end()
        if pos != len(text) or not text:
            raise ConfigurationError(f"cannot read duration {value!r}; write e.g. '1 scan', '500ms', '10s + 2 scans'")
        return cls(ns, scans, text)

    def resolve(self, scan_ns: int) -> int:
        """The duration in ns for a given scan time."""
        return self.ns + round(self.scans * scan_ns)

    def __str__(self) -> str:
        return self.text or format_ns(self.ns)


# --------------------------------------------------------------------------------------------
# Evaluation context and verdicts
# --------------------------------------------------------------------------------------------


@dataclass
class Context:
    """What a check reads: the trace, the scan time, the program's static facts."""

    trace: Trace
    scan_ns: int
    analysis: Any = None
    start_ns: int = 0
    end_ns: int = 0

    @classmethod
    def of(cls, trace: Trace, analysis: Any = None) -> Context:
        scan = int(trace.meta.get("cycle_ns") or 1_000_000)
        end = int(trace.meta.get("end_ns") or (trace.end_times[-1] if len(trace) else 0))
        return cls(trace, scan, analysis, 0, end)

    def t(self, ns: int) -> str:
        return format_ns(int(ns))


@dataclass
class Verdict:
    """The result of one check."""

    passed: bool
    message: str
    at_ns: int | None = None
    signals: list[str] = field(default_factory=list)
    window: tuple[int, int] | None = None


def _signals_of(*items: Any) -> list[str]:
    names: list[str] = []
    for item in items:
        for name in getattr(item, "signals", lambda: [])():
            if name not in names:
                names.append(name)
    return names


# --------------------------------------------------------------------------------------------
# Conditions: a Bool per trace row
# --------------------------------------------------------------------------------------------


class Condition:
    """True or false in each scan (trace row)."""

    def rows(self, ctx: Context) -> np.ndarray:  # pragma: no cover - overridden
        raise NotImplementedError

    def describe(self) -> str:  # pragma: no cover - overridden
        raise NotImplementedError

    def signals(self) -> list[str]:
        return []

    def __invert__(self) -> Condition:
        return Not(self)


def as_condition(item: str | Condition) -> Condition:
    """A tag name means "that Bool tag is TRUE"."""
    if isinstance(item, Condition):
        return item
    if isinstance(item, str):
        return On(item)
    raise ConfigurationError(f"expected a condition such as 'D1', off('D1') or value('CV') > 0, not {item!r}")


@dataclass(frozen=True)
class On(Condition):
    name: str

    def rows(self, ctx: Context) -> np.ndarray:
        return ctx.trace.column(self.name).astype(bool)

    def describe(self) -> str:
        return self.name

    def signals(self) -> list[str]:
        return [self.name]


@dataclass(frozen=True)
class Not(Condition):
    inner: Condition

    def rows(self, ctx: Context) -> np.ndarray:
        return ~self.inner.rows(ctx)

    def describe(self) -> str:
        inner = self.inner.describe()
        return f"not {inner}" if " " not in inner else f"not ({inner})"

    def signals(self) -> list[str]:
        return self.inner.signals()


@dataclass(frozen=True)
class AllOf(Condition):
    parts: tuple[Condition, ...]

    def rows(self, ctx: Context) -> np.ndarray:
        out = np.ones(len(ctx.trace), dtype=bool)
        for p in self.parts:
            out &= p.rows(ctx)
        return out

    def describe(self) -> str:
        return " and ".join(_paren(p) for p in self.parts)

    def signals(self) -> list[str]:
        return _signals_of(*self.parts)


@dataclass(frozen=True)
class AnyOf(Condition):
    parts: tuple[Condition, ...]

    def rows(self, ctx: Context) -> np.ndarray:
        out = np.zeros(len(ctx.trace), dtype=bool)
        for p in self.parts:
            out |= p.rows(ctx)
        return out

    def describe(self) -> str:
        return " or ".join(_paren(p) for p in self.parts)

    def signals(self) -> list[str]:
        return _signals_of(*self.parts)


def _paren(c: Condition) -> str:
    text = c.describe()
    return f"({text})" if " and " in text or " or " in text else text


@dataclass(frozen=True)
class Compare(Condition):
    name: str
    op: str
    other: Any

    def rows(self, ctx: Context) -> np.ndarray:
        left = ctx.trace.column(self.name).astype(np.float64)
        right = ctx.trace.column(self.other.name).astype(np.float64) if isinstance(self.other, Value) else self.other
        return {
            "<": np.less,
            "<=": np.less_equal,
            ">": np.greater,
            ">=": np.greater_equal,
            "==": np.equal,
            "!=": np.not_equal,
        }[self.op](left, right)

    def describe(self) -> str:
        other = self.other.name if isinstance(self.other, Value) else repr(self.other)
        return f"{self.name} {self.op} {other}"

    def signals(self) -> list[str]:
        return [self.name] + ([self.other.name] if isinstance(self.other, Value) else [])


@dataclass(frozen=True)
class Value:
    """A numeric signal to compare: ``value("CISLO") > 0``, ``value("LED") == value("TLACIDLO")``."""

    name: str

    def __gt__(self, other: Any) -> Compare:  # type: ignore[override]
        return Compare(self.name, ">", other)

    def __ge__(self, other: Any) -> Compare:  # type: ignore[override]
        return Compare(self.name, ">=", other)

    def __lt__(self, other: Any) -> Compare:  # type: ignore[override]
        return Compare(self.name, "<", other)

    def __le__(self, other: Any) -> Compare:  # type: ignore[override]
        return Compare(self.name, "<=", other)

    def __eq__(self, other: Any) -> Compare:  # type: ignore[override]
        return Compare(self.name, "==", other)

    def __ne__(self, other: Any) -> Compare:  # type: ignore[override]
        return Compare(self.name, "!=", other)

    def __hash__(self) -> int:
        return hash(self.name)


def value(name: str) -> Value:
    """A numeric tag to compare."""
    return Value(name)


def off(name: str) -> Condition:
    """The Bool tag is FALSE."""
    return Not(On(name))


def on(name: str) -> Condition:
    """The Bool tag is TRUE (a plain name means the same)."""
    return On(name)


def all_of(*items: str | Condition) -> Condition:
    """Every condition holds in the scan."""
    return AllOf(tuple(as_condition(i) for i in items))


def any_of(*items: str | Condition) -> Condition:
    """At least one condition holds in the scan."""
    return AnyOf(tuple(as_condition(i) for i in items))


def not_(item: str | Condition) -> Condition:
    """The condition does not hold."""
    return Not(as_condition(item))


def implies(a: str | Condition, b: str | Condition) -> Condition:
    """In every scan where ``a`` holds, ``b`` holds too."""
    return AnyOf((Not(as_condition(a)), as_condition(b)))


def same(a: str, b: str) -> Condition:
    """Two tags have the same value in the scan (an output follows an input)."""
    return Compare(a, "==", Value(b))


# --------------------------------------------------------------------------------------------
# Occurrences: points in time
# --------------------------------------------------------------------------------------------


class Occurrences:
    """A set of instants: edges of a signal, plant events, scenario actions."""

    def times(self, ctx: Context) -> np.ndarray:  # pragma: no cover - overridden
        raise NotImplementedError

    def describe(self) -> str:  # pragma: no cover - overridden
        raise NotImplementedError

    def signals(self) -> list[str]:
        return []

    def within(self, span: str | int) -> ResponseBuilder:
        """The response must come no later than ``span`` after each trigger."""
        return ResponseBuilder(self, Span(0, 0, "0"), Span.parse(span), f"within {Span.parse(span)}")

    def between(self, lo: str | int, hi: str | int) -> ResponseBuilder:
        """The response must come between ``lo`` and ``hi`` after each trigger."""
        a, b = Span.parse(lo), Span.parse(hi)
        return ResponseBuilder(self, a, b, f"between {a} and {b}")


@dataclass(frozen=True)
class Edge(Occurrences):
    name: str
    rising: bool

    def times(self, ctx: Context) -> np.ndarray:
        tr = ctx.trace
        return tr.rises(self.name) if self.rising else tr.falls(self.name)

    def describe(self) -> str:
        return f"{self.name} {'rises' if self.rising else 'falls'}"

    def signals(self) -> list[str]:
        return [self.name]


@dataclass(frozen=True)
class Becomes(Occurrences):
    condition: Condition

    def times(self, ctx: Context) -> np.ndarray:
        rows = self.condition.rows(ctx)
        if len(rows) < 2:
            return np.zeros(0, dtype=np.int64)
        idx = np.nonzero(rows[1:] & ~rows[:-1])[0] + 1
        return ctx.trace.times[idx]

    def describe(self) -> str:
        return f"{self.condition.describe()} becomes true"

    def signals(self) -> list[str]:
        return self.condition.signals()


@dataclass(frozen=True)
class EventOccurrences(Occurrences):
    kind: str
    subject: str | None = None
    source: str | None = None

    def times(self, ctx: Context) -> np.ndarray:
        events = ctx.trace.events_of(self.kind, None, self.source)
        if self.subject is not None:
            events = [e for e in events if self.subject in (e.subject, e.part)]
        return np.array([e.t_ns for e in events], dtype=np.int64)

    def describe(self) -> str:
        who = f" {self.subject}" if self.subject else ""
        if self.source == "scenario":
            return f"the operator's {self.kind}{who}"
        return f"'{self.kind}'{who}"


@dataclass(frozen=True)
class Calls(Occurrences):
    """The starts of a task's executions (``calls("OB30")``), from the trace's task column."""

    task: str

    def times(self, ctx: Context) -> np.ndarray:
        number = int(self.task.upper().lstrip("OB"))
        tr = ctx.trace
        return tr.times[tr.tasks == number]

    def describe(self) -> str:
        return f"{self.task} is called"


@dataclass(frozen=True)
class Either(Occurrences):
    """Whichever of several occurrences happens (``either(rises("A"), falls("B"))``)."""

    parts: tuple[Occurrences, ...]

    def times(self, ctx: Context) -> np.ndarray:
        return np.unique(np.concatenate([p.times(ctx) for p in self.parts])) if self.parts else np.zeros(0, np.int64)

    def describe(self) -> str:
        return " or ".join(p.describe() for p in self.parts)

    def signals(self) -> list[str]:
        return _signals_of(*self.parts)


def calls(task: str) -> Calls:
    """The instants an interrupt task runs (its trace rows): ``rises("LED").within("2ms").after(calls("OB30"))``."""
    return Calls(task)


def either(*occurrences: Occurrences) -> Either:
    """The union of several occurrences."""
    return Either(tuple(occurrences))


def rises(name: str) -> Edge:
    """The instants a Bool tag goes FALSE -> TRUE (an output at the end of the scan that wrote it)."""
    return Edge(name, True)


def falls(name: str) -> Edge:
    """The instants a Bool tag goes TRUE -> FALSE."""
    return Edge(name, False)


def becomes(condition: str | Condition) -> Becomes:
    """The scans in which a condition turns true."""
    return Becomes(as_condition(condition))


def event(kind: str, subject: str | None = None) -> EventOccurrences:
    """Plant events: ``event("part fell off")``, ``event("part entered", "S2")``."""
    return EventOccurrences(kind, subject, "plant")


def action(verb: str, target: str | None = None) -> EventOccurrences:
    """Scenario actions: ``action("press", "ACK")``, ``action("jam")``."""
    return EventOccurrences(verb, target, "scenario")


# --------------------------------------------------------------------------------------------
# Checks
# --------------------------------------------------------------------------------------------


class Check:
    """A statement about a run that passes or fails with a reason."""

    name: str | None = None
    weight: float = 1.0
    extra_signals: tuple[str, ...] = ()

    def evaluate(self, ctx: Context) -> Verdict:  # pragma: no cover - overridden
        raise NotImplementedError

    def describe(self) -> str:  # pragma: no cover - overridden
        raise NotImplementedError

    def named(self, name: str) -> Check:
        """Give the check the name reports show."""
        self.name = name
        return self

    def plotting(self, *signals: str) -> Check:
        """Add signals to the timing diagram of a failure (for context: the button beside the LED)."""
        self.extra_signals = tuple(signals)
        return self

    def points(self, weight: float) -> Check:
        """How much the check is worth (default 1)."""
        self.weight = weight
        return self

    @property
    def title(self) -> str:
        return self.name or self.describe()


@dataclass
class ResponseBuilder:
    response: Occurrences
    lo: Span
    hi: Span
    wording: str

    def after(self, trigger: Occurrences, *, provided: str | Condition | None = None, at_least: int = 1) -> Response:
        """Each ``trigger`` (where ``provided`` holds in its scan) must be followed by the response."""
        return Response(
            self.response,
            self.lo,
            self.hi,
            self.wording,
            trigger,
            as_condition(provided) if provided is not None else None,
            at_least,
        )


@dataclass
class Response(Check):
    response: Occurrences
    lo: Span
    hi: Span
    wording: str
    trigger: Occurrences
    provided: Condition | None = None
    at_least: int = 1
    name: str | None = None
    weight: float = 1.0

    def describe(self) -> str:
        extra = f" while {self.provided.describe()}" if self.provided is not None else ""
        return f"{self.response.describe()} {self.wording} after {self.trigger.describe()}{extra}"

    def evaluate(self, ctx: Context) -> Verdict:
        triggers = self.trigger.times(ctx)
        if self.provided is not None and len(triggers):
            rows = self.provided.rows(ctx)
            idx = np.clip(np.searchsorted(ctx.trace.times, triggers, side="right") - 1, 0, len(rows) - 1)
            triggers = triggers[rows[idx]]
        signals = _signals_of(self.trigger, self.response, self.provided)
        if len(triggers) < self.at_least:
            return Verdict(
                False,
                f"expected {self.trigger.describe()} at least {self.at_least} time(s) to check "
                f"that {self.describe()}; it happened {len(triggers)} time(s)",
                None,
                signals,
            )
        answers = self.response.times(ctx)
        lo, hi = self.lo.resolve(ctx.scan_ns), self.hi.resolve(ctx.scan_ns)
        for when in triggers:
            ok = answers[(answers >= when + lo) & (answers <= when + hi)]
            if len(ok) == 0:
                later = answers[answers >= when]
                if len(later):
                    happened = f"it happened {ctx.t(later[0] - when)} after it, at {ctx.t(later[0])}"
                else:
                    happened = "it did not happen afterwards"
                return Verdict(
                    False,
                    f"after {self.trigger.describe()} at {ctx.t(when)}, expected {self.response.describe()} "
                    f"{self.wording} (between {ctx.t(when + lo)} and {ctx.t(when + hi)}); {happened}",
                    int(when),
                    signals,
                    (int(when + lo), int(when + hi)),
                )
        return Verdict(True, f"{len(triggers)} time(s), each answered {self.wording}", None, signals)


def _first_bad(ctx: Context, bad: np.ndarray, window: tuple[int, int] | None, tolerance: Span | None) -> int | None:
    times = ctx.trace.times
    if window is not None:
        bad = bad & (times >= window[0]) & (times < window[1])
    if not bad.any():
        return None
    if tolerance is None:
        return int(np.argmax(bad))
    limit = tolerance.resolve(ctx.scan_ns)
    ends = ctx.trace.end_times
    k, n = 0, len(bad)
    while k < n:
        if bad[k]:
            j = k
            while j + 1 < n and bad[j + 1]:
                j += 1
            if ends[j] - times[k] > limit:
                return k
            k = j + 1
        else:
            k += 1
    return None


def _window(ctx: Context, window: tuple[Span, Span] | None) -> tuple[int, int] | None:
    if window is None:
        return None
    return window[0].resolve(ctx.scan_ns), window[1].resolve(ctx.scan_ns)


def _row_values(ctx: Context, k: int, names: Sequence[str]) -> str:
    tr = ctx.trace
    parts = []
    for name in names:
        v = tr.column(name)[k]
        shown = ("TRUE" if v else "FALSE") if tr.types.get(name) == "bool" else _num(v)
        parts.append(f"{name}={shown}")
    return ", ".join(parts)


def _num(v: Any) -> str:
    f = float(v)
    return str(int(f)) if f.is_integer() else f"{f:.6g}"


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

    def describe(self) -> str:
        text = f"never {self.what.describe()}"
        if self.tolerance is not None:
            text += f" for more than {self.tolerance}"
        return text

    def evaluate(self, ctx: Context) -> Verdict:
        signals = self.what.signals()
        if isinstance(self.what, Occurrences):
            times = self.what.times(ctx)
            w = _window(ctx, self.window)
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
        k = _first_bad(ctx, self.what.rows(ctx), _window(ctx, self.window), self.tolerance)
        if k is None:
            return Verdict(True, "it never held", None, signals)
        t0 = int(ctx.trace.times[k])
        return Verdict(
            False,
            f"expected never {self.what.describe()}; it held in the scan at {ctx.t(t0)} "
            f"({_row_values(ctx, k, signals)})",
            t0,
            signals,
            (t0, int(ctx.trace.end_times[k])),
        )


def never(what: str | Condition | Occurrences) -> Never:
    """The condition holds in no scan, or the event never happens."""
    return Never(what if isinstance(what, Occurrences) else as_condition(what))


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

    def describe(self) -> str:
        return f"always {self.condition.describe()}"

    def evaluate(self, ctx: Context) -> Verdict:
        signals = self.condition.signals()
        k = _first_bad(ctx, ~self.condition.rows(ctx), _window(ctx, self.window), self.tolerance)
        if k is None:
            return Verdict(True, "it held in every scan", None, signals)
        t0 = int(ctx.trace.times[k])
        return Verdict(
            False,
            f"expected always {self.condition.describe()}; it failed in the scan at {ctx.t(t0)} "
            f"({_row_values(ctx, k, signals)})",
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

    def describe(self) -> str:
        if self.release is not None:
            return f"{self.condition.describe()} holds until {self.release.describe()}"
        return f"{self.condition.describe()} holds for at least {self.minimum}"

    def evaluate(self, ctx: Context) -> Verdict:
        rows = self.condition.rows(ctx)
        times, ends = ctx.trace.times, ctx.trace.end_times
        signals = _signals_of(self.condition, self.release)
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
    return Eventually(what if isinstance(what, Occurrences) else as_condition(what))


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
        return ctx.t(v) if self.unit == "ns" else _num(v)

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
            return Verdict(False, f"expected {self.describe()}; there was nothing to measure", None, self.sources)
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

    return Quantity(f"number of times {occ.describe()}", compute, occ.signals())


def spacing(what: Occurrences) -> Quantity:
    """Every time between two successive occurrences: ``spacing(rises("Takt1s")).between("1s", "1s + 1 scan")``."""

    def compute(ctx: Context) -> tuple[list[float], list[int]]:
        times = what.times(ctx)
        return [float(b - a) for a, b in pairwise(times)], [int(t) for t in times[:-1]]

    q = Quantity(f"time between successive '{what.describe()}'", compute, what.signals(), unit="ns")
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

    q = Quantity(f"time {cond.describe()} stays true", compute, cond.signals(), unit="ns")
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

    return Quantity(f"fraction of time {cond.describe()}", compute, cond.signals())


def final(name: str) -> Quantity:
    """The value of a tag at the end of the run: ``final("MOTOR.SEKUNDY").equals(15)``."""

    def compute(ctx: Context) -> tuple[float | None, list[int]]:
        col = ctx.trace.column(name)
        if len(col) == 0:
            return None, []
        return float(col[-1]), [int(ctx.trace.times[-1])]

    return Quantity(f"{name} at the end", compute, [name])


def measure(
    label: str, compute: Callable[[Trace], float | list[float] | None], *signals: str, unit: str = ""
) -> Quantity:
    """A number an instructor computes from the trace with Python: the escape hatch of the language.

    ``compute(trace)`` returns a number (or a list of numbers, each checked); ``signals`` are plotted
    when the check fails. Example: the hours meter counts the seconds the belt ran::

        measure("SEKUNDY minus seconds with D1 on", lambda tr: ..., "MOTOR.SEKUNDY", "D1").between(-1, 1)
    """

    def run(ctx: Context) -> tuple[Any, list[int]]:
        value = compute(ctx.trace)
        if isinstance(value, (list, tuple)):
            return [float(v) for v in value], []
        return (None if value is None else float(value)), []

    q = Quantity(label, run, list(signals), unit=unit)
    return q


def value_at(name: str, when: str | int) -> Quantity:
    """The value of a tag at a time of the run."""

    def compute(ctx: Context) -> tuple[float | None, list[int]]:
        t = Span.parse(when).resolve(ctx.scan_ns)
        return float(ctx.trace.value_at(name, t)), [t]

    return Quantity(f"{name} at {when}", compute, [name])


@dataclass
class StaticCheck(Check):
    """A statement about the program text rather than its run."""

    instruction: str
    forbidden: bool = True
    name: str | None = None
    weight: float = 1.0

    def describe(self) -> str:
        word = {"SET": "SET coils", "RESET": "RESET coils", "EDGE": "edge instructions"}.get(
            self.instruction, self.instruction
        )
        return f"the program uses no {word}" if self.forbidden else f"the program uses {word}"

    def evaluate(self, ctx: Context) -> Verdict:
        analysis = ctx.analysis
        if analysis is None:
            return Verdict(False, "the program could not be analysed")
        used = analysis.uses(self.instruction)
        if self.instruction == "SET" and used:
            where = ", ".join(f"{target} (line {line})" for target, line in analysis.set_coils[:3])
            detail = f"; SET coils: {where}"
        elif self.instruction == "RESET" and used:
            where = ", ".join(f"{target} (line {line})" for target, line in analysis.reset_coils[:3])
            detail = f"; RESET coils: {where}"
        else:
            detail = ""
        if used == self.forbidden:
            return Verdict(False, f"expected {self.describe()}{detail}")
        return Verdict(True, self.describe())


def program_uses_no(instruction: str) -> StaticCheck:
    """Static check: the program has no ``SET`` (``if c: t.X = True``), ``RESET`` or ``EDGE`` instruction."""
    return StaticCheck(instruction, True)


def evaluate_all(checks: Iterable[Check], trace: Trace, analysis: Any = None) -> list[tuple[Check, Verdict]]:
    """Evaluate checks on one trace; an error in a check becomes a failed verdict, never a crash."""
    ctx = Context.of(trace, analysis)
    out = []
    for check in checks:
        try:
            verdict = check.evaluate(ctx)
            verdict.signals += [s for s in check.extra_signals if s not in verdict.signals]
        except Exception as exc:  # noqa: BLE001 - a check's own bug is reported, not raised
            verdict = Verdict(False, f"the check could not be evaluated: {type(exc).__name__}: {exc}")
        out.append((check, verdict))
    return out
