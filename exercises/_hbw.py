"""What 4.3.18 (the stacker crane) grades beyond plain conditions: every request served where it asked, and the
program's position estimates against the crane's true position; and the operator at the HMI.

A **request** is the rising edge of ``DATA.Poziadavka_naloz`` (put in) or ``DATA.Poziadavka_vyloz`` (take out) in
the trace, with the ``DATA.x``, ``DATA.y`` it was made with. The plant says what the fork did (``part put down`` /
``part picked up`` with the place); the program's bits are not trusted for it.
"""

from __future__ import annotations

import random
from dataclasses import dataclass

import numpy as np

from plants.hbw import X_CAMS, Y_CAMS, Y_ZONE, Z_CAMS, Z_ZONE
from plcsim.check import Check, Context, Verdict
from plcsim.check.base import Names
from plcsim.scenario import after_event, place, remove, write

PUT, TAKE = "DATA.Poziadavka_naloz", "DATA.Poziadavka_vyloz"
FORK_MOVES = ("part put down", "part picked up", "part fell off")
DONE = "2s..2.2s"
"""How long after the fork put a part down (or lifted it) the operator takes a retrieved part off the fork and
starts the next request: the task gives the program this long to bring the fork back to z2 and clear the request."""
STEPS = 0.4
"""Seconds between the operator's steps of one request (the part on the fork, DATA.x and DATA.y, the request),
each drawn in a 0.2 s window that never overlaps the next, whatever was drawn before."""


# --------------------------------------------------------------------------------------------
# The operator at the HMI
# --------------------------------------------------------------------------------------------

Request = tuple[str, int, int]
"""``("put", column, row)`` or ``("take", column, row)``."""


def operator(requests: list[Request], *, stocked: dict[str, str] | None = None, first: str = "2s..2.2s") -> list:
    """The actions of an operator who makes ``requests`` one after the other at the HMI.

    From a start (``first`` for the first request, :data:`DONE` after the fork put the previous part down or
    lifted it for the next), in steps of :data:`STEPS`: a retrieved part is taken off the fork; for a put-in a new
    part is put on it; ``DATA.x`` and ``DATA.y`` are written; the request is set. ``stocked`` maps places to the
    parts on them before the run.
    """
    actions: list = [place(part, at=where, t="0s", noise=False) for where, part in (stocked or {}).items()]
    on_place = dict(stocked or {})
    when: dict = {"t": first}
    on_fork = None
    new = 0
    for kind, x, y in requests:
        if on_fork is not None:
            actions.append(remove(on_fork, **_later(when, 0)))
            on_fork = None
        where = f"R{x}{y}"
        if kind == "put":
            new += 1
            part = f"n{new}"
            actions.append(place(part, at="fork", noise=False, **_later(when, 1)))
            on_place[where] = part
        else:
            part = on_fork = on_place.pop(where)
        actions += [
            write("DATA.x", float(x), **_later(when, 2)),
            write("DATA.y", float(y), **_later(when, 2)),
            write(PUT if kind == "put" else TAKE, True, **_later(when, 3)),
        ]
        when = {"when": after_event("part put down" if kind == "put" else "part picked up", part), "delay": DONE}
    return actions


def _later(when: dict, step: int) -> dict:
    """The ``step``-th window after ``when`` (a time or a trigger with a delay, both ranges of seconds): shifted by
    ``step`` × (:data:`STEPS` + the range's width), so that it begins after the previous window ends."""
    key = "t" if "t" in when else "delay"
    a, b = (float(v.rstrip("s")) for v in when[key].split(".."))
    lo = a + step * (STEPS + b - a)
    window = {key: f"{lo:g}s..{lo + b - a:g}s"}
    return window if key == "t" else {"when": when["when"], **window}


def random_requests(seed: int, n: int, stocked: set[tuple[int, int]] = frozenset()) -> list[Request]:
    """``n`` requests drawn with ``seed``: a put-in to a free place or a take-out from an occupied one (a put-in
    with the chance of the free places among the nine), starting from the places in ``stocked``."""
    rng = random.Random(seed)
    full = set(stocked)
    out: list[Request] = []
    for _ in range(n):
        free = [(x, y) for x in (1, 2, 3) for y in (1, 2, 3) if (x, y) not in full]
        kind = "put" if rng.random() < len(free) / 9 else "take"
        x, y = rng.choice(sorted(free) if kind == "put" else sorted(full))
        (full.add if kind == "put" else full.discard)((x, y))
        out.append((kind, x, y))
    return out


# --------------------------------------------------------------------------------------------
# The checks
# --------------------------------------------------------------------------------------------


def requests_in(trace) -> list[tuple[str, int, int, int, int]]:
    """Every request in the run: (``put``/``take``, column, row, made at ns, cleared at ns or -1)."""
    out = []
    for tag, kind in ((PUT, "put"), (TAKE, "take")):
        for t in trace.rises(tag):
            x, y = (round(float(trace.value_at(f"DATA.{c}", int(t)))) for c in "xy")
            falls = [int(f) for f in trace.falls(tag) if f > t]
            out.append((kind, x, y, int(t), falls[0] if falls else -1))
    return sorted(out, key=lambda r: r[3])


@dataclass
class Served(Check):
    """Every request is served: the fork puts the part down on (takes it from) the requested place and nowhere
    else before the next request, and the program clears the request once the fork is back at z2, not before."""

    name: str | None = None
    weight: float = 1.0

    def names(self) -> Names:
        signals = (PUT, TAKE, "DATA.x", "DATA.y", "plant:Z.s")
        return Names(signals, tuple((k, None) for k in FORK_MOVES)) + super().names()

    def describe(self) -> str:
        return "every request is served at the requested place, then cleared with the fork back at z2"

    def evaluate(self, ctx: Context) -> Verdict:
        trace = ctx.trace
        signals = [PUT, TAKE, "DATA.x", "DATA.y", "plant:X.s", "plant:Y.s", "plant:Z.s"]
        reqs = requests_in(trace)
        if not reqs:
            return Verdict(False, "expected requests to serve; none was made", None, signals)
        moves = [e for e in trace.events if e.source == "plant" and e.kind in FORK_MOVES]
        end = int(trace.end_times[-1])
        for k, (kind, x, y, t0, cleared) in enumerate(reqs):
            t1 = reqs[k + 1][3] if k + 1 < len(reqs) else end
            what = f"the {'put-in' if kind == 'put' else 'take-out'} request for [{x},{y}] made at {ctx.t(t0)}"
            mine = [e for e in moves if t0 <= e.t_ns < t1]
            want = ("part put down" if kind == "put" else "part picked up", f"R{x}{y}")
            if [(e.kind, e.subject) for e in mine] != [want]:
                seen = ", ".join(f"{e.kind} at {e.subject} ({ctx.t(e.t_ns)})" for e in mine) or "nothing"
                return Verdict(
                    False, f"{what}: the fork did {seen}; expected {want[0]} at {want[1]}", t0, signals, (t0, t1)
                )
            if cleared < 0 or (cleared >= t1 and k + 1 < len(reqs)):
                return Verdict(False, f"{what} was never cleared", t0, signals, (t0, t1))
            if cleared < mine[0].t_ns:
                return Verdict(
                    False, f"{what} was cleared at {ctx.t(cleared)}, before the part was moved", cleared, signals
                )
            z = float(trace.value_at("plant:Z.s", cleared))
            if abs(z - Z_CAMS["z2"]) > Z_ZONE:
                return Verdict(
                    False,
                    f"{what} was cleared at {ctx.t(cleared)} with the fork at Z = {z:.1f} mm, not back at z2",
                    cleared,
                    signals,
                )
        return Verdict(True, f"{len(reqs)} request(s), each served where it asked", None, signals)


AXES = {"X": ("OS_X", X_CAMS), "Y": ("OS_Y", Y_CAMS), "Z": ("OS_Z", Z_CAMS)}


@dataclass
class Estimate(Check):
    """``OS_<axis>.aktualna`` holds the true position (within 1 scan) once the axis has seen its first sensor: the
    sensor's number on a sensor, half-way values between two, 0.5 before the first and n + 0.5 past the last."""

    axis: str = "X"
    name: str | None = None
    weight: float = 1.0

    def names(self) -> Names:
        db, cams = AXES[self.axis]
        return Names((f"{db}.aktualna", f"plant:{self.axis}.s", *cams)) + super().names()

    def describe(self) -> str:
        return f"{AXES[self.axis][0]}.aktualna follows the true position of {self.axis}"

    def truth(self, trace) -> np.ndarray:
        """Per row: the position the estimate must hold (NaN before the first sensor was seen)."""
        _, cams = AXES[self.axis]
        centres = np.array(list(cams.values()))
        s = np.asarray(trace.column(f"plant:{self.axis}.s"), dtype=float)
        between = np.searchsorted(centres, s) + 0.5  # past k centres: k + 0.5
        on = np.zeros(len(s), dtype=bool)
        out = between.astype(float)
        for k, name in enumerate(cams, start=1):
            lit = np.asarray(trace.column(name), dtype=bool)
            out[lit] = float(k)
            on |= lit
        seen = np.maximum.accumulate(on)
        out[~seen] = np.nan
        return out

    def evaluate(self, ctx: Context) -> Verdict:
        db, cams = AXES[self.axis]
        trace = ctx.trace
        signals = [f"{db}.aktualna", f"plant:{self.axis}.s", *cams]
        want = self.truth(trace)
        got = np.asarray(trace.column(f"{db}.aktualna"), dtype=float)
        bad = ~np.isnan(want) & (got != want)
        lasting = bad & np.concatenate(([False], bad[:-1]))  # wrong in this scan and the one before
        if lasting.any():
            row = int(np.argmax(lasting)) - 1
            t = int(trace.times[row])
            return Verdict(
                False,
                f"{db}.aktualna = {got[row]:g} at {ctx.t(t)}, but the crane's {self.axis} was at {want[row]:g} "
                f"({self.axis} = {float(trace.column(f'plant:{self.axis}.s')[row]):.1f} mm)",
                t,
                signals,
            )
        return Verdict(True, f"{db}.aktualna followed {self.axis}", None, signals)


@dataclass
class FinalStep(Check):
    """Criterion 3: the step control ends a request in its last step, ``DATA.KROK`` = 6, when it clears it."""

    name: str | None = None
    weight: float = 1.0

    def names(self) -> Names:
        return Names((PUT, TAKE, "DATA.KROK")) + super().names()

    def describe(self) -> str:
        return "DATA.KROK is 6 when a request is cleared"

    def evaluate(self, ctx: Context) -> Verdict:
        signals = [PUT, TAKE, "DATA.KROK"]
        cleared = [(kind, x, y, c) for kind, x, y, _, c in requests_in(ctx.trace) if c >= 0]
        for kind, x, y, c in cleared:
            step = int(ctx.trace.value_at("DATA.KROK", c))
            if step != 6:
                what = "put-in" if kind == "put" else "take-out"
                return Verdict(
                    False, f"the {what} request for [{x},{y}] was cleared at {ctx.t(c)} in step {step}", c, signals
                )
        if not cleared:
            return Verdict(False, "expected a request to be cleared; none was", None, signals)
        return Verdict(True, f"{len(cleared)} request(s) cleared in step 6", None, signals)


@dataclass
class OneRowInRack(Check):
    """Criterion 2: with the fork in the rack (forward of z2) Y moves only between the two sensors of one row,
    below and above its shelf (odd ↔ even), never through a second shelf."""

    name: str | None = None
    weight: float = 1.0

    def names(self) -> Names:
        return Names(("plant:Y.s", "plant:Z.s")) + super().names()

    def describe(self) -> str:
        return "in the rack Y moves only between the two sensors of one row"

    def evaluate(self, ctx: Context) -> Verdict:
        signals = ["plant:Y.s", "plant:Z.s", "y_hore", "y_dole", "z3"]
        trace = ctx.trace
        y = np.asarray(trace.column("plant:Y.s"), dtype=float)
        inside = np.asarray(trace.column("plant:Z.s"), dtype=float) > Z_CAMS["z2"] + Z_ZONE + 0.5
        lows, highs = list(Y_CAMS.values())[0::2], list(Y_CAMS.values())[1::2]
        bands = [(lo - Y_ZONE - 2.0, hi + Y_ZONE + 2.0) for lo, hi in zip(lows, highs, strict=True)]
        edges = np.flatnonzero(np.diff(np.concatenate(([0], inside.astype(np.int8), [0]))))
        for start, stop in zip(edges[0::2], edges[1::2], strict=True):
            low, high = float(y[start:stop].min()), float(y[start:stop].max())
            if not any(a <= low and high <= b for a, b in bands):
                t0, t1 = int(trace.times[start]), int(trace.times[stop - 1])
                return Verdict(
                    False,
                    f"with the fork in the rack from {ctx.t(t0)} to {ctx.t(t1)} Y went from {low:.1f} to {high:.1f} "
                    f"mm: more than one row's two sensors",
                    t0,
                    signals,
                    (t0, t1),
                )
        return Verdict(True, "Y stayed within one row whenever the fork was in the rack", None, signals)
