"""A light barrier (through-beam photo sensor) in a side view; a component of a side-view rig.

The beam crosses the belt perpendicular to the drawing plane, so in the side view it is a small spot: a sensor
box ``width`` wide (along the travel) and ``height`` high, centred ``x`` along the line and ``y`` above the base.
It is event-driven: the rig's collision handler calls :meth:`LightBarrier.enter` when a part starts to overlap the
beam and :meth:`LightBarrier.leave` when it stops (pymunk's ``begin``/``separate``); the barrier keeps the parts in
the beam in an insertion-ordered dict (an ordered set: it never depends on string hashing, so event order is the
same in every process) and counts both callbacks. The barrier is **interrupted** while any part overlaps it. The
plant reports the physical state (True = interrupted); NO/NC is the wiring's job.

A fault can shift the beam (``dx``, misaligned sensor); the station where an operator puts a part stays where it
was, so the sensor's edges move by ``dx / v``. The moved beam re-detects its parts in the next physics step, and only
the difference is reported (:meth:`LightBarrier.shift_sensor`).
"""

from __future__ import annotations

from typing import Any

import pymunk

from plants.components import draw
from plants.components.collide import BEAM_CAT, CT_BEAM, PART_CAT
from plants.components.component import Host
from plants.components.workpiece import Part
from plcsim.plant import Drawable, SignalSpec


class LightBarrier:
    """One beam. ``x``/``y``: nominal centre of the beam spot (mm); ``dx``: fault shift (mm)."""

    EVENTS = frozenset({"part entered", "part left"})

    def __init__(
        self, name: str, x: float, y: float, *, width: float = 2.0, height: float = 2.0, doc: str = ""
    ) -> None:
        if width <= 0 or height <= 0:
            raise ValueError(f"light barrier {name}: width and height must be > 0")
        self.name = name
        self.x = float(x)
        self.y = float(y)
        self.width = float(width)
        self.height = float(height)
        self.doc = doc
        self.shape: pymunk.Poly | None = None
        self._sensors: dict[str, Any] = {self.name: False}
        self._reset_state()

    def _reset_state(self) -> None:
        self.dx = 0.0
        self.parts: dict[str, None] = {}  # part ids in the beam, in the order they entered
        self.begins = 0  # begin callbacks counted (entries)
        self.separates = 0  # separate callbacks counted (exits)
        self.rebuilding: dict[str, None] | None = None  # members before a shift, until the next step re-detects
        self.shape = None
        self._spots: dict[tuple[bool, float], Drawable] = {}

    @property
    def x_actual(self) -> float:
        """Where the beam really is (nominal + fault shift)."""
        return self.x + self.dx

    @property
    def interrupted(self) -> bool:
        return bool(self.parts)

    @property
    def count(self) -> int:
        return len(self.parts)

    # --- the component protocol --------------------------------------------------------------------------------
    def specs(self) -> list[SignalSpec]:
        return [SignalSpec(self.name, "sensor", doc=self.doc)]

    def subjects(self) -> set[str]:
        return {self.name}

    def reset(self, host: Host) -> bool:
        self._reset_state()
        self.attach(host.space)
        self._sensors = host.sensors
        host.sensors[self.name] = False
        return False

    def actuate(self, host: Host, signal: str, value: Any) -> bool:
        return False

    def advance(self, host: Host, dt: float) -> bool:
        return False

    def static_drawables(self) -> list[Drawable]:
        return [
            draw.line(
                f"sensors/{self.name}", [(self.x, self.y - 10.0), (self.x, self.y + 30.0)], draw.SENSOR, self.name
            ),
            draw.label(f"sensors/{self.name}/label", self.x, self.y + 36.0, self.name),
        ]

    def dynamic_drawables(self) -> list[Drawable]:
        """The beam spot, red while interrupted (drawn over the parts)."""
        on = self._sensors[self.name]
        key = (on, self.x_actual)
        spot = self._spots.get(key)
        if spot is None:  # drawables are frozen, so one per state is shared by every frame
            color = draw.BEAM_CUT if on else draw.BEAM_FREE
            spot = self._spots[key] = draw.circle(f"beams/{self.name}", self.x_actual, self.y, 2.5, color, self.name)
        return [spot]

    # --- parts in the beam (called from the rig's collision handler) --------------------------------------------
    def enter(self, host: Host, part: Part) -> None:
        if part.state == "off" or part.state == "gone":
            return
        self.begins += 1
        if part.id in self.parts:
            return
        self.parts[part.id] = None
        if self.rebuilding is None:
            host.sensors[self.name] = True
            host.emit("part entered", self.name, part.id)

    def leave(self, host: Host, part: Part) -> None:
        pid = part.id
        if pid not in self.parts:
            return
        self.separates += 1
        del self.parts[pid]
        if self.rebuilding is None:
            host.sensors[self.name] = bool(self.parts)
            host.emit("part left", self.name, pid)

    def part_gone(self, host: Host, pid: str) -> None:
        """A part left the plant (removed, fallen or knocked off): it is no longer in the beam."""
        if self.rebuilding is not None:
            self.parts.pop(pid, None)
            if pid in self.rebuilding:
                del self.rebuilding[pid]
                host.sensors[self.name] = bool(self.rebuilding)
                host.emit("part left", self.name, pid)
        elif pid in self.parts:
            del self.parts[pid]
            self.separates += 1
            host.sensors[self.name] = bool(self.parts)
            host.emit("part left", self.name, pid)

    # --- the fault ---------------------------------------------------------------------------------------------
    def shift_sensor(self, host: Host, name: str, dx_mm: float) -> None:
        """Fault: the beam is mounted ``dx_mm`` off its nominal place (absolute, not cumulative). It is moved at
        once; which parts it sees is re-detected by the next physics step (if there are parts), and only the
        difference is reported then (:meth:`settle`): no spurious edge for a part that stays in the beam."""
        dx = float(dx_mm)
        if dx == self.dx:
            return
        if self.rebuilding is None:
            self.rebuilding = dict(self.parts)
        self.parts = {}
        self.dx = dx
        host.space.remove(self.shape)  # separate callbacks: nothing is a member any more, they are ignored
        self.attach(host.space)
        host.after_step(self)

    def settle(self, host: Host) -> None:
        """After the physics step that re-detected the parts in the moved beam: report the difference."""
        old, self.rebuilding = self.rebuilding or {}, None
        for pid in old:
            if pid not in self.parts:
                host.emit("part left", self.name, pid, cause="sensor shifted")
        for pid in self.parts:
            if pid not in old:
                host.emit("part entered", self.name, pid, cause="sensor shifted")
        host.sensors[self.name] = bool(self.parts)

    def make_shape(self, space: pymunk.Space) -> pymunk.Poly:
        """A static sensor box at the beam's actual position (not yet added to the space)."""
        x, y, hw, hh = self.x_actual, self.y, self.width / 2, self.height / 2
        shape = pymunk.Poly(space.static_body, [(x - hw, y - hh), (x + hw, y - hh), (x + hw, y + hh), (x - hw, y + hh)])
        shape.sensor = True
        shape.collision_type = CT_BEAM
        shape.filter = pymunk.ShapeFilter(categories=BEAM_CAT, mask=PART_CAT)
        shape.owner = self  # read back in the rig's collision callbacks
        return shape

    def attach(self, space: pymunk.Space) -> pymunk.Poly:
        self.shape = self.make_shape(space)
        space.add(self.shape)
        return self.shape
