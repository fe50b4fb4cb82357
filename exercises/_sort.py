"""What the colour sorter 4.3.17 grades against the plant's own account: where each object is, per scan.

The program's DB DATA keeps five positions (occupied + the object's type). The plant reports each object entering
and leaving the five barriers and landing in a bin; from those :class:`Positions` says, scan by scan, which object
is at which position, and the conditions here compare the program's bits with it (criterion 5).
:class:`OnlyAfter` grades criterion 3's "a piston is only activated when an object of its type has just passed its
barrier".
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from exercises._truth import GONE
from plcsim.check import Check, Condition, Context, Verdict
from plcsim.check.base import Names
from plcsim.trace import Trace

BARRIERS = ("OS1_Vstup", "OS2_Detekcia", "OS3_Farba1", "OS4_Farba2", "OS5_Farba3")
OCCUPIED = ("POZ1_OBS_Nakladanie", "POZ2_OBS_Detekcia", "POZ3_OBS_Farba1", "POZ4_OBS_Farba2", "POZ5_OBS_Farba3")
TYPES = (None, "POZ2_DETEKCIA", "POZ3_FARBA1", "POZ4_FARBA2", "POZ5_FARBA3")
PISTON_AT = (None, None, "Piest1_Farba1", "Piest2_Farba2", "Piest3_Farba3")
"""Per position (0 = loading … 4 = colour 3): its barrier, occupancy bit, type tag and the piston behind it."""

EVENTS = (("part placed", None), ("part entered", None), ("part in bin", None))


def colours(trace: Trace) -> dict[str, int]:
    """The colour each object was placed with (0 if it has none)."""
    return {
        e.part: int(e.data.get("colour", 0))
        for e in trace.events
        if e.source == "plant" and e.kind == "part placed" and e.part
    }


NO_OBJECT = -1
"""What :func:`at_position` gives for a position with no object (0 is an object of none of the three colours)."""


def at_position(trace: Trace, k: int) -> np.ndarray:
    """Per scan, the colour of the object at position ``k`` (0: a colour out of every interval, :data:`NO_OBJECT`:
    none): from its entering barrier ``k`` until it enters the next barrier, lands in a bin or leaves the plant."""
    colour = colours(trace)
    since: dict[str, int] = {}
    spans: list[tuple[str, int, int]] = []
    for e in trace.events:
        if e.source != "plant" or not e.part:
            continue
        if e.kind == "part entered" and e.subject == BARRIERS[k] and e.part not in since:
            since[e.part] = e.t_ns
        elif e.part in since and (
            (k + 1 < len(BARRIERS) and e.kind == "part entered" and e.subject == BARRIERS[k + 1])
            or e.kind == "part in bin"
            or e.kind in GONE
        ):
            spans.append((e.part, since.pop(e.part), e.t_ns))
    end = int(trace.end_times[-1]) + 1 if len(trace) else 0
    spans += [(p, t, end) for p, t in since.items()]
    times = trace.times
    out = np.full(len(times), NO_OBJECT, dtype=np.int64)
    for part, t0, t1 in spans:
        out[(times >= t0) & (times < t1)] = colour.get(part, 0)
    return out


def _position_words(k: int) -> str:
    """Position ``k`` in the sensors' physical terms: the barriers are NC, FALSE while an object is in the beam."""
    until = f"{BARRIERS[k + 1]}'s" if k + 1 < len(BARRIERS) else "its bin"
    return f"from {BARRIERS[k]}'s beam to {until}; a barrier reads FALSE while an object is in its beam: NC"


@dataclass(frozen=True)
class Unmarked(Condition):
    """An object is at position ``k`` and the position is not marked occupied."""

    k: int

    def rows(self, ctx: Context) -> np.ndarray:
        return (at_position(ctx.trace, self.k) != NO_OBJECT) & ~ctx.trace.column(f"DATA.{OCCUPIED[self.k]}").astype(
            bool
        )

    def describe(self) -> str:
        return f"an object at position {self.k + 1} ({_position_words(self.k)}) with DATA.{OCCUPIED[self.k]} FALSE"

    def signals(self) -> list[str]:
        return [f"DATA.{OCCUPIED[self.k]}", BARRIERS[self.k]]

    def names(self) -> Names:
        return Names(tuple(self.signals()), EVENTS)


@dataclass(frozen=True)
class Phantom(Condition):
    """Position ``k`` is marked occupied with no object there, and its piston (if any) is not out: the 1 s pulse
    that pushes an object off clears its position only when it ends."""

    k: int

    def rows(self, ctx: Context) -> np.ndarray:
        bad = ctx.trace.column(f"DATA.{OCCUPIED[self.k]}").astype(bool) & (at_position(ctx.trace, self.k) == NO_OBJECT)
        piston = PISTON_AT[self.k]
        return bad & ~ctx.trace.column(piston).astype(bool) if piston else bad

    def describe(self) -> str:
        out = " with its piston back" if PISTON_AT[self.k] else ""
        return f"DATA.{OCCUPIED[self.k]} TRUE with no object at position {self.k + 1} ({_position_words(self.k)}){out}"

    def signals(self) -> list[str]:
        return [f"DATA.{OCCUPIED[self.k]}", *([PISTON_AT[self.k]] if PISTON_AT[self.k] else [])]

    def names(self) -> Names:
        return Names(tuple(self.signals()), EVENTS)


@dataclass(frozen=True)
class WrongType(Condition):
    """Position ``k``'s type is not the colour of the object there (0 for a colour out of every interval), or not
    0 with no object there (a stale type would be pushed off with the next object that reads out of range); its
    piston's pulse may end first."""

    k: int

    def rows(self, ctx: Context) -> np.ndarray:
        colour = at_position(ctx.trace, self.k)
        kind = ctx.trace.column(f"DATA.{TYPES[self.k]}").astype(np.int64)
        piston = PISTON_AT[self.k]
        pushing = ctx.trace.column(piston).astype(bool) if piston else np.zeros(len(colour), dtype=bool)
        present = colour != NO_OBJECT
        return (kind != np.where(present, colour, 0)) & (present | ~pushing)

    def describe(self) -> str:
        return (
            f"DATA.{TYPES[self.k]} differs from the colour of the object at position {self.k + 1} "
            "(0: none, or of no colour)"
        )

    def signals(self) -> list[str]:
        return [f"DATA.{TYPES[self.k]}", "FARBA", *([PISTON_AT[self.k]] if PISTON_AT[self.k] else [])]

    def names(self) -> Names:
        return Names(tuple(self.signals()), EVENTS)


@dataclass
class OnlyAfter(Check):
    """Every rise of ``piston`` comes within ``scans`` scans after an object of colour ``colour`` left ``barrier``
    ("the position is occupied and its sensor free: the object has just passed")."""

    piston: str
    barrier: str
    colour: int
    scans: int = 1
    name: str | None = None
    weight: float = 1.0

    def names(self) -> Names:
        events = (("part placed", None), ("part left", self.barrier))
        return Names((self.piston, self.barrier), events) + super().names()

    def describe(self) -> str:
        return f"{self.piston} goes out only just after an object of colour {self.colour} left {self.barrier}"

    def evaluate(self, ctx: Context) -> Verdict:
        colour = colours(ctx.trace)
        passed = np.array(
            [
                e.t_ns
                for e in ctx.trace.events
                if e.source == "plant"
                and e.kind == "part left"
                and e.subject == self.barrier
                and colour.get(e.part or "") == self.colour
            ],
            dtype=np.int64,
        )
        col = ctx.trace.column(self.piston).astype(bool)
        rises = ctx.trace.times[col & ~np.concatenate(([False], col[:-1]))]
        signals = [self.piston, self.barrier]
        for t in rises:
            before = passed[(passed <= t) & (passed >= t - self.scans * ctx.scan_ns)]
            if not len(before):
                last = passed[passed <= t]
                why = f"the last one left at {ctx.t(last[-1])}" if len(last) else "none had left it"
                return Verdict(
                    False,
                    f"{self.piston} went out at {ctx.t(t)}, not within {self.scans} scan(s) after an object of "
                    f"colour {self.colour} left {self.barrier} ({why})",
                    int(t),
                    signals,
                )
        return Verdict(True, f"{len(rises)} stroke(s), each just after its object passed", None, signals)


@dataclass
class NoMissort(Check):
    """No object lands in a colour bin other than its own (``bin<k>`` for colour k; ``unsorted`` is not a
    mis-sort): what a sorter must not do even when it cannot keep up."""

    name: str | None = None
    weight: float = 1.0

    def names(self) -> Names:
        return Names((), (("part in bin", None),)) + super().names()

    def describe(self) -> str:
        return "every object that lands in a colour bin is of that bin's colour"

    def evaluate(self, ctx: Context) -> Verdict:
        landed = [e for e in ctx.trace.events if e.source == "plant" and e.kind == "part in bin"]
        for e in landed:
            if e.subject.startswith("bin") and e.subject != f"bin{e.data.get('colour')}":
                return Verdict(
                    False,
                    f"object {e.part} of colour {e.data.get('colour')} landed in {e.subject} at {ctx.t(e.t_ns)}",
                    int(e.t_ns),
                    list(PISTON_AT[2:]),
                )
        return Verdict(True, f"{len(landed)} object(s) landed, none in another colour's bin", None, [])
