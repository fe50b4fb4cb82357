"""What the plant knows and a program should: conditions that compare tags with the plant's truth.

The checker language reads tags; these read the plant's own events too. :class:`Parts` counts the
parts in a stretch of the line (the truth a program's count or occupancy bit must follow) and
:class:`EdgeBalance` counts rising edges of one input minus another's, as the PLC saw them.
Used by 4.3.6, 4.3.9 and 4.3.10.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from plcsim.check import Condition, Context

GONE = ("part removed", "part fell off", "part knocked off")


@dataclass(frozen=True)
class Parts:
    """The number of parts in a stretch of the line, per scan, from the plant's events.

    A part is in the stretch from its first ``part entered <start>`` until its first
    ``part entered <end>`` (``end=None``: until it leaves the plant: removed, fallen or knocked off).
    Parts named in ``ignore`` (an operator's hand modelled as a block) are not counted. Events are
    stamped with the time the PLC's next scan reads them, so the count changes in the very scan
    whose input image shows the beam change.
    """

    start: str
    end: str | None = None
    ignore: tuple[str, ...] = ()
    label: str = ""

    def counts(self, ctx: Context) -> np.ndarray:
        entered: dict[str, int] = {}
        left: dict[str, int] = {}
        for e in ctx.trace.events:
            if e.source != "plant" or not e.part or e.part in self.ignore:
                continue
            if e.kind == "part entered" and e.subject == self.start:
                entered.setdefault(e.part, e.t_ns)
            elif (
                e.part in entered
                and e.part not in left
                and ((e.kind == "part entered" and e.subject == self.end) or e.kind in GONE)
            ):
                left[e.part] = e.t_ns
        times = ctx.trace.times
        n = np.zeros(len(times), dtype=np.int64)
        for part, t_in in entered.items():
            n += times >= t_in
            if part in left:
                n -= times >= left[part]
        return n

    def describe(self) -> str:
        if self.label:
            return self.label
        where = f"between {self.start} and {self.end}" if self.end else f"past {self.start}"
        return f"parts {where}"

    # conditions
    def __gt__(self, k: int) -> Condition:  # type: ignore[override]
        return _PartsCompare(self, ">", k)

    def __eq__(self, k: object) -> Condition:  # type: ignore[override]
        return _PartsCompare(self, "==", k)

    def __le__(self, k: int) -> Condition:  # type: ignore[override]
        return _PartsCompare(self, "<=", k)

    def __hash__(self) -> int:
        return hash((self.start, self.end, self.ignore))

    def signals(self) -> list[str]:
        """The sensors that bound the stretch (plotted with a failed check when they are traced tags)."""
        return [self.start] + ([self.end] if self.end else [])


@dataclass(frozen=True)
class _PartsCompare(Condition):
    parts: Parts
    op: str
    k: int

    def rows(self, ctx: Context) -> np.ndarray:
        n = self.parts.counts(ctx)
        return {">": n > self.k, "==": n == self.k, "<=": n <= self.k}[self.op]

    def describe(self) -> str:
        return f"({self.parts.describe()}) {self.op} {self.k}"

    def signals(self) -> list[str]:
        return self.parts.signals()


@dataclass(frozen=True)
class CountIs(Condition):
    """A numeric tag equals a count computed from the run (:class:`Parts` or :class:`EdgeBalance`)."""

    name: str
    truth: Parts | EdgeBalance

    def rows(self, ctx: Context) -> np.ndarray:
        return ctx.trace.column(self.name).astype(np.int64) == self.truth.counts(ctx)

    def describe(self) -> str:
        return f"{self.name} == {self.truth.describe()}"

    def signals(self) -> list[str]:
        return [self.name, *self.truth.signals()]


@dataclass(frozen=True)
class FlagIs(Condition):
    """A Bool tag is TRUE exactly while the stretch holds at least one part."""

    name: str
    truth: Parts

    def rows(self, ctx: Context) -> np.ndarray:
        return ctx.trace.column(self.name).astype(bool) == (self.truth.counts(ctx) > 0)

    def describe(self) -> str:
        return f"{self.name} == ({self.truth.describe()} > 0)"

    def signals(self) -> list[str]:
        return [self.name, *self.truth.signals()]


@dataclass(frozen=True)
class EdgeBalance:
    """Per scan: rising edges of ``up`` minus rising edges of ``down`` so far, as the PLC's input image saw them."""

    up: str
    down: str

    def counts(self, ctx: Context) -> np.ndarray:
        out = np.zeros(len(ctx.trace), dtype=np.int64)
        for name, sign in ((self.up, 1), (self.down, -1)):
            col = ctx.trace.column(name).astype(bool)
            rise = col & ~np.concatenate(([False], col[:-1]))
            out += sign * np.cumsum(rise)
        return out

    def describe(self) -> str:
        return f"(rising edges of {self.up}) - (rising edges of {self.down})"

    def signals(self) -> list[str]:
        return [self.up, self.down]


def parts_equal(name: str, truth: Parts | EdgeBalance) -> Condition:
    """``name`` equals the count in every scan."""
    return CountIs(name, truth)


def flag_matches(name: str, truth: Parts) -> Condition:
    """``name`` is TRUE exactly while a part is in the stretch."""
    return FlagIs(name, truth)
