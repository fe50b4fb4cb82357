"""The pieces every check is made of: durations with scans, the evaluation context, verdicts."""

from __future__ import annotations

import re
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import Any, ClassVar

import numpy as np

from plcsim.core.errors import ConfigurationError, defined_at
from plcsim.core.literals import duration_ns, format_ns
from plcsim.trace.facade import Trace

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
    """The result of one check. ``nothing_to_check``: it failed because the run gave it nothing to check (no
    trigger, nothing to measure), which a wrong program can cause and a scenario that cannot show the behaviour
    too; the grade says how to apply the check only where it applies (``only(...)``)."""

    passed: bool
    message: str
    at_ns: int | None = None
    signals: list[str] = field(default_factory=list)
    window: tuple[int, int] | None = None
    nothing_to_check: bool = False


@dataclass(frozen=True)
class Names:
    """The names a check (or a part of one) reads, so that an exercise can check them when it is loaded.

    ``signals`` are trace columns, ``events`` plant events and ``actions`` scenario actions as
    ``(kind, subject)`` pairs (subject None: any), ``tasks`` the OBs whose calls it counts.
    """

    signals: tuple[str, ...] = ()
    events: tuple[tuple[str, str | None], ...] = ()
    actions: tuple[tuple[str, str | None], ...] = ()
    tasks: tuple[str, ...] = ()

    def __add__(self, other: Names) -> Names:
        def merged(a: tuple[Any, ...], b: tuple[Any, ...]) -> tuple[Any, ...]:
            return tuple(dict.fromkeys(a + b))

        return Names(
            merged(self.signals, other.signals),
            merged(self.events, other.events),
            merged(self.actions, other.actions),
            merged(self.tasks, other.tasks),
        )


def names_of(*items: Any) -> Names:
    """The names every item reads (None and items without names are skipped)."""
    out = Names()
    for item in items:
        if hasattr(item, "names"):
            out += item.names()
    return out


def signals_of(*items: Any) -> list[str]:
    names: list[str] = []
    for item in items:
        for name in getattr(item, "signals", lambda: [])():
            if name not in names:
                names.append(name)
    return names


class Check:
    """A statement about a run that passes or fails with a reason."""

    name: str | None = None
    weight: float = 1.0
    requirement: str | None = None
    extra_signals: tuple[str, ...] = ()
    exercise_conditions: tuple[Any, ...] = ()
    as_exercise_condition: ClassVar[Callable[[Any], Any]]
    """How :meth:`exercised_by` reads each thing it is given: an occurrence as it is, anything else as a
    condition. :mod:`plcsim.check.occurrences` sets it: it knows both kinds and sits above this module, which
    therefore imports neither (the package imports it before any check can be built)."""

    def __post_init__(self) -> None:
        self.defined_at = defined_at()  # where the instructor wrote it, for the errors of load-time validation

    def evaluate(self, ctx: Context) -> Verdict:  # pragma: no cover - overridden
        raise NotImplementedError

    def describe(self) -> str:  # pragma: no cover - overridden
        raise NotImplementedError

    def names(self) -> Names:
        """The names the check reads: its own parts' (each check adds them) and the signals it plots."""
        return Names(tuple(self.extra_signals)) + names_of(*self.exercise_conditions)

    def named(self, name: str) -> Check:
        """Give the check the name reports show."""
        self.name = name
        return self

    def grades(self, requirement: str) -> Check:
        """Name the words of the task the check grades (``"The belt stops when the object reaches S2"``): the
        exercise refuses to load unless its task text states them, and ``plcsim show`` prints them with the
        check, so that a student reads every requirement a grade depends on."""
        self.requirement = requirement
        return self

    def plotting(self, *signals: str) -> Check:
        """Add signals to the timing diagram of a failure (for context: the button beside the LED)."""
        self.extra_signals = tuple(signals)
        return self

    def exercised_by(self, *whats: Any) -> Check:
        """Count the check only in scenarios in which one of ``whats`` happened: an occurrence
        (``rises("D3")``) or a condition (a tag name, ``value("N") > 1``) true in some scan. Without
        it the generic rule of :mod:`plcsim.check.exercised` applies alone."""
        self.exercise_conditions = tuple(self.as_exercise_condition(w) for w in whats)
        return self

    def points(self, weight: float) -> Check:
        """How much the check is worth (default 1)."""
        self.weight = weight
        return self

    @property
    def title(self) -> str:
        return self.name or self.describe()


def first_bad_row(ctx: Context, bad: np.ndarray, window: tuple[int, int] | None, tolerance: Span | None) -> int | None:
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


def window_ns(ctx: Context, window: tuple[Span, Span] | None) -> tuple[int, int] | None:
    if window is None:
        return None
    return window[0].resolve(ctx.scan_ns), window[1].resolve(ctx.scan_ns)


def row_values(ctx: Context, k: int, names: Sequence[str]) -> str:
    tr = ctx.trace
    parts = []
    for name in names:
        v = tr.column(name)[k]
        shown = ("TRUE" if v else "FALSE") if tr.types.get(name) == "bool" else show_number(v)
        parts.append(f"{name}={shown}")
    return ", ".join(parts)


def show_number(v: Any) -> str:
    f = float(v)
    return str(int(f)) if f.is_integer() else f"{f:.6g}"
