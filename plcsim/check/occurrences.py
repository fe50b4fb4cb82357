"""Occurrences: points in time (edges, plant events, scenario actions, task calls), and responses
to them (``X.within("1 scan").after(Y)``)."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from plcsim.check.base import Check, Context, Names, Span, Verdict, names_of, signals_of
from plcsim.check.conditions import Condition, as_condition
from plcsim.trace.facade import Trace

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

    def names(self) -> Names:
        """The names it reads (edges and conditions: their signals)."""
        return Names(tuple(self.signals()))

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

    def names(self) -> Names:
        if self.source == "scenario":
            return Names(actions=((self.kind, self.subject),))
        return Names(events=((self.kind, self.subject),))

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
        tr = ctx.trace
        return tr.times[tr.rows_of(self.task)]

    def describe(self) -> str:
        return f"{self.task} is called"

    def names(self) -> Names:
        return Names(tasks=(self.task,))


@dataclass(frozen=True)
class Either(Occurrences):
    """Whichever of several occurrences happens (``either(rises("A"), falls("B"))``)."""

    parts: tuple[Occurrences, ...]

    def times(self, ctx: Context) -> np.ndarray:
        return np.unique(np.concatenate([p.times(ctx) for p in self.parts])) if self.parts else np.zeros(0, np.int64)

    def describe(self) -> str:
        return " or ".join(p.describe() for p in self.parts)

    def signals(self) -> list[str]:
        return signals_of(*self.parts)

    def names(self) -> Names:
        return names_of(*self.parts)


@dataclass(frozen=True)
class Seen(Occurrences):
    """The starts of the scans that saw other occurrences (the first execution of ``task`` starting at or
    after each): the instant the program could first react, from which a reaction time counts."""

    what: Occurrences
    task: str = "OB1"

    def times(self, ctx: Context) -> np.ndarray:
        return seen_at(ctx.trace, self.what.times(ctx), self.task)

    def describe(self) -> str:
        return f"the {self.task} scan that saw {self.what.describe()}"

    def signals(self) -> list[str]:
        return self.what.signals()


def seen_at(trace: Trace, t_ns: np.ndarray | list[int], task: str = "OB1") -> np.ndarray:
    """The start of the first ``task`` execution at or after each time (times no scan saw are left out).

    An HMI write at 150 ms is seen by the 10 ms scan that starts at 150 ms; one at 155 ms by the scan at 160 ms:

    >>> from plcsim.trace.facade import Trace
    >>> tr = Trace(["M"], types={"M": "bool"})
    >>> for k in range(20):
    ...     tr.add_row(k * 10_000_000, (k + 1) * 10_000_000, 1, (False,))
    >>> seen_at(tr, [150_000_000, 155_000_000, 999_000_000]).tolist()
    [150000000, 160000000]
    """
    starts = trace.times[trace.rows_of(task)]
    k = np.searchsorted(starts, np.asarray(t_ns, dtype=np.int64), side="left")
    return starts[k[k < len(starts)]]


def seen(what: Occurrences, task: str = "OB1") -> Seen:
    """The scans that saw ``what``: ``rises("LED").within("1 scan").after(seen(action("write", "ACK")))``
    counts the scan from the scan that read the HMI write, not from the write itself."""
    return Seen(what, task)


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


def occurrence_or_condition(item: str | Condition | Occurrences) -> Condition | Occurrences:
    """An occurrence as it is, anything else as a condition (a tag name: that tag is TRUE): what
    ``never``, ``eventually`` and ``exercised_by`` accept."""
    return item if isinstance(item, Occurrences) else as_condition(item)


Check.as_exercise_condition = staticmethod(occurrence_or_condition)


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

    def names(self) -> Names:
        return names_of(self.trigger, self.response, self.provided) + super().names()

    def describe(self) -> str:
        extra = f" while {self.provided.describe()}" if self.provided is not None else ""
        return f"{self.response.describe()} {self.wording} after {self.trigger.describe()}{extra}"

    def evaluate(self, ctx: Context) -> Verdict:
        triggers = self.trigger.times(ctx)
        if self.provided is not None and len(triggers):
            rows = self.provided.rows(ctx)
            triggers = triggers[rows[ctx.trace.rows_started_by(triggers)]]
        signals = signals_of(self.trigger, self.response, self.provided)
        if len(triggers) < self.at_least:
            return Verdict(
                False,
                f"expected {self.trigger.describe()} at least {self.at_least} time(s) to check "
                f"that {self.describe()}; it happened {len(triggers)} time(s)",
                None,
                signals,
                nothing_to_check=True,
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
