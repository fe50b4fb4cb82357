"""A high-bay rack and the fork of a stacker crane that serves it: places, parts as bodies, collisions.

The rack stands at depth ``z`` ∈ [``front``, ``front + depth``] behind the crane's travel; it has columns at the X
positions ``columns`` and shelves whose tops are at the heights ``shelves``. A shelf is slotted for the fork's two
tines, so the empty fork passes it; a part does not. The crane's three axes (:class:`~plants.components.axis.Axis`)
are read, not owned: ``x`` (travel along the rack), ``y`` (the height of the fork's top) and ``z`` (the fork's
depth, + into the rack). :meth:`Rack.follow` is called after every step in which an axis moved.

A part is a rigid body with three places to be: it **rides the fork** (it moves with it), **sits on a place**
``(column, row)``, or **falls** (it is gone: ``part fell off``). What happens, as the fork moves:

* the fork, carrying a part, goes down through a shelf's top inside the rack: with the fork in far enough to carry
  the part's centre over the shelf (``z ≥ seat``) the part is **put down** on that place (``part put down``,
  subject the place); less far in, the part tips over the shelf's edge and falls (``part fell off``);
* the empty fork comes up through a shelf's top under a stored part, in far enough: it **picks** it (``part picked
  up``); less far in, the tines lift one edge and the part falls;
* **collisions** (``collision``, once when a contact begins, ``data["what"]`` says what hit what): inside the rack
  the fork off a column by more than ``tolerance`` (it hits a post: X moved, or Z went in beside a column); the
  tines against a stored part; a carried part against a shelf or a stored part. The crane is not stopped by a
  collision (the drives are stronger than the model), so a program that causes one goes on being graded.

An operator puts a part on the fork outside the rack (station ``fork``) or stocks a place before the run
(station ``R<column><row>``), and takes a part from either.

>>> from plants.components.axis import Axis
>>> from plants.components.component import Bench
>>> x, y, z = Axis("X", 0.0, 400.0, start=100.0, speed=60.0), Axis("Y", 0.0, 300.0, start=70.0, speed=30.0), \\
...     Axis("Z", -80.0, 90.0, start=0.0, speed=40.0)
>>> rack = Rack("rack", x, y, z, columns=(100.0, 220.0), shelves=(60.0, 160.0))
>>> host = Bench(); _ = [a.reset(host) for a in (x, y, z)]; _ = rack.reset(host)
>>> rack.put_on_fork(host, "p1")
>>> z.s = 80.0; rack.follow(host); y.s = 50.0; rack.follow(host)
>>> rack.stored, [(e.kind, e.subject) for e in host.events]
({(1, 1): 'p1'}, [('part placed', 'fork'), ('part put down', 'R11')])
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

from plants.components.axis import Axis
from plants.components.component import Host
from plcsim.plant import Drawable, SignalSpec

TINE = 6.0  # thickness of the fork's tines, mm (their top is the axis Y's position)
SLAB = 8.0  # thickness of a shelf under its top, mm


class Rack:
    """The rack and the fork (see the module docstring).

    Args:
        name: the component's name (the subject of collisions with the frame).
        x: the crane's travel along the rack.
        y: the fork's height (the top of its tines).
        z: the fork's depth (+ into the rack).
        columns: the X position of each column's centre, mm (column 1 first).
        shelves: the height of each row's shelf top, mm (row 1, the lowest, first).
        front: where the rack begins along Z, mm.
        depth: how deep a place is, mm.
        part_size: (width along X, depth along Z, height) of a part, mm.
        tolerance: how far off a column's centre the fork may be inside the rack, mm.
        seat: the fork's Z from which a part put down or picked is carried by the shelf or the fork.
    """

    EVENTS = frozenset({"part placed", "part removed", "part picked up", "part put down", "part fell off", "collision"})

    def __init__(
        self,
        name: str,
        x: Axis,
        y: Axis,
        z: Axis,
        *,
        columns: Sequence[float],
        shelves: Sequence[float],
        front: float = 40.0,
        depth: float = 80.0,
        part_size: tuple[float, float, float] = (40.0, 40.0, 30.0),
        tolerance: float = 20.0,
        seat: float = 60.0,
    ) -> None:
        self.name = name
        self.x, self.y, self.z = x, y, z
        self.columns = tuple(float(c) for c in columns)
        self.shelves = tuple(float(s) for s in shelves)
        self.front, self.depth = float(front), float(depth)
        self.part_size = part_size
        self.tolerance = float(tolerance)
        self.seat = float(seat)
        self.places = {
            f"R{i}{j}": (i, j) for i in range(1, len(self.columns) + 1) for j in range(1, len(self.shelves) + 1)
        }

    # -- the component protocol ------------------------------------------------------------------------------
    def specs(self) -> list[SignalSpec]:
        return []

    def subjects(self) -> set[str]:
        return {self.name, "fork", *self.places}

    def reset(self, host: Host) -> bool:
        self.on_fork: str | None = None
        self.stored: dict[tuple[int, int], str] = {}
        self.contacts: set[str] = set()
        self._last = (self.y.s, self.z.s)
        return False

    def reset_pose(self) -> None:
        """The axes were put somewhere before the run (no motion: nothing is carried, put down or hit)."""
        self._last = (self.y.s, self.z.s)

    def actuate(self, host: Host, signal: str, value: Any) -> bool:
        return False

    def advance(self, host: Host, dt: float) -> bool:
        self.follow(host)
        return False

    # -- the operator ----------------------------------------------------------------------------------------
    def fork_in_rack(self) -> bool:
        """Whether the fork (or the part on it) reaches into the rack."""
        return self.z.s + self.part_size[1] / 2 > self.front

    def put_on_fork(self, host: Host, part: str) -> None:
        if self.on_fork is not None:
            raise ValueError(f"the fork already carries {self.on_fork}")
        if self.fork_in_rack():
            raise ValueError("the fork is in the rack: a part can be put on it only in front of the rack")
        self.on_fork = part
        host.emit("part placed", "fork", part)

    def stock(self, host: Host, place: str, part: str) -> None:
        where = self.places[place]
        if where in self.stored:
            raise ValueError(f"place {place} already holds {self.stored[where]}")
        self.stored[where] = part
        host.emit("part placed", place, part)

    def take(self, host: Host, target: str) -> str:
        """Take a part away (by its id, ``fork`` or a place's name); returns its id."""
        if target == "fork" or target == self.on_fork:
            if self.on_fork is None:
                raise ValueError("the fork carries no part")
            part, self.on_fork = self.on_fork, None
            host.emit("part removed", "fork", part)
            return part
        for where, part in self.stored.items():
            if target in (part, self.place_name(where)):
                del self.stored[where]
                host.emit("part removed", self.place_name(where), part)
                return part
        raise KeyError(f"no part {target!r} on the fork or in the rack")

    @staticmethod
    def place_name(where: tuple[int, int]) -> str:
        return f"R{where[0]}{where[1]}"

    # -- what the fork does ----------------------------------------------------------------------------------
    def column_at(self) -> int | None:
        """The column the fork is in front of (within ``tolerance``), 1-based, or None."""
        for i, c in enumerate(self.columns, start=1):
            if abs(self.x.s - c) <= self.tolerance:
                return i
        return None

    def follow(self, host: Host) -> None:
        """The axes moved: carry, put down, pick, fall and collide as the module docstring says."""
        y0, _ = self._last
        y, z = self.y.s, self.z.s
        self._last = (y, z)
        if not self.fork_in_rack():
            if self.contacts:
                self.contacts = set()
            return
        col = self.column_at()
        now: set[str] = set()
        if col is None:
            now.add("the fork hit a post of the rack")
        else:
            if y != y0:  # (a shelf's top is passed only by a fork that moved up or down)
                self._shelves_passed(host, col, y0, y, z)
            now |= self._touching(col, y)
        for what in sorted(now - self.contacts):
            host.emit("collision", self.name, self.on_fork, what=what, x=self.x.s, y=y, z=z)
        self.contacts = now

    def _shelves_passed(self, host: Host, col: int, y0: float, y: float, z: float) -> None:
        for row, top in enumerate(self.shelves, start=1):
            place = self.place_name((col, row))
            if y0 > top >= y and self.on_fork is not None:  # going down through the shelf's top, carrying
                part, self.on_fork = self.on_fork, None
                if z >= self.seat and (col, row) not in self.stored:
                    self.stored[(col, row)] = part
                    host.emit("part put down", place, part, z=z)
                else:
                    host.emit("part fell off", place, part, z=z)
            elif y0 < top <= y and self.on_fork is None and (col, row) in self.stored:  # coming up under a part
                part = self.stored.pop((col, row))
                if z >= self.seat:
                    self.on_fork = part
                    host.emit("part picked up", place, part, z=z)
                else:
                    host.emit("part fell off", place, part, z=z)

    def _touching(self, col: int, y: float) -> set[str]:
        out = set()
        height = self.part_size[2]
        for row, top in enumerate(self.shelves, start=1):
            stored = (col, row) in self.stored
            if stored and y - TINE < top + height and y > top:
                out.add(f"the fork hit the part on {self.place_name((col, row))}")
            if self.on_fork is not None:
                if y < top and y + height > top - SLAB:
                    out.add(f"the part on the fork hit the shelf of {self.place_name((col, row))}")
                elif stored and y < top + height and y + height > top:
                    out.add(f"the part on the fork hit the part on {self.place_name((col, row))}")
        return out

    # -- drawing ---------------------------------------------------------------------------------------------
    def static_drawables(self) -> list[Drawable]:
        return []

    def dynamic_drawables(self) -> list[Drawable]:
        return []
