"""A single-acting pneumatic piston: a monostable valve, a force-limited stroke out, a spring return, optional reed
switches at its ends.

The plate is a dynamic pymunk body (no rotation) on a ``GrooveJoint`` whose ends are the mechanical end stops, so it
pushes parts by contact and stops against them: a piston can only push as hard as its force limit (a part held
against a fence stops the plate; a jammed piston does not move). The valve switches ``valve_s`` after its output
changes. With the valve open and the supply above ``threshold`` (a fraction of full pressure, from ``supply()``:
a compressor, or full pressure if none) the plate is driven out at ``extend_speed`` with at most
``force_n · pressure``; otherwise the spring drives it back at ``retract_speed`` with at most ``spring_n``. The drive
is a speed servo capped at that force (pneumatic cylinders with throttled exhaust move at a near-constant speed).

Coordinates: the stroke ``s`` (mm) runs from 0 (retracted; the plate's front face at ``origin``) to ``stroke``
along the unit vector ``direction``. End switches are :class:`~plants.components.limit_switch.LimitSwitch` zones on
``s``. Events: ``piston extended`` when ``s`` arrives at ``full - 2 mm``, ``piston retracted`` when it arrives back
within 0.5 mm of 0 (an arrival counts again once the plate has backed off that end by 3 mm: a piston hammering at
its front gives one event per blow), ``piston jammed`` for the fault.

**Parked at rest** (``park=True``): a piston back at its rear end with the valve closed does nothing the solver
needs to compute, so its plate leaves the physics: the body and its groove are taken out of the space and a static
copy of the plate takes its place (a part pushed against it still meets a wall, as against the plate held at its end
stop). The first ``advance`` after a wake-up (the valve switches, a fault) puts the body back where it was, at rest.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import pymunk

from plants.components import chipmunk, draw
from plants.components.collide import CT_PLATE, PART_CAT, PLATE_CAT
from plants.components.component import Host
from plants.components.limit_switch import LimitSwitch
from plants.components.sketch import Sketch
from plcsim.plant import Drawable, SignalSpec

NEWTON = 1000.0  # kg·mm/s² (the notes' units: mm, kg, s)
MASS_KG = 0.02  # plate and rod
EXTENDED_WITHIN = 2.0  # mm: "piston extended" once this close to the full stroke
RETRACTED_WITHIN = 0.5  # mm
LEAVE = 3.0  # mm: backed off an end this far, the next arrival there is a new one


class Piston:
    """One piston with valve output ``valve`` (True = extend).

    Args:
        name: the piston (subject of its events).
        valve: the actuator (PLC output) of its monostable valve.
        origin: (x, y) of the plate's front face centre when retracted (mm).
        direction: unit vector of the stroke.
        stroke: the groove's length (mm): the mechanical end stop.
        full: the full working stroke (default ``stroke``): ``piston extended`` from ``full - 2 mm`` on.
        plate: (width across the stroke, thickness) of the pusher plate (mm).
        extend_speed: mm/s out.
        retract_speed: mm/s back.
        force_n: the force limit out, at full pressure (N).
        spring_n: the spring's force limit back (N).
        valve_s: valve switching delay (s).
        threshold: the fraction of full pressure below which it does not move out.
        supply: a callable giving the pressure fraction now (None: always full).
        rear: an optional end switch at the rear (its name becomes a sensor).
        front: an optional end switch at the front.
        park: take the plate out of the solver while it rests retracted (see the module docstring).
    """

    EVENTS = frozenset({"piston extended", "piston retracted", "piston jammed"})

    def __init__(
        self,
        name: str,
        valve: str,
        *,
        origin: tuple[float, float],
        direction: tuple[float, float],
        stroke: float,
        full: float | None = None,
        plate: tuple[float, float] = (50.0, 6.0),
        extend_speed: float = 80.0,
        retract_speed: float = 67.0,
        force_n: float = 5.0,
        spring_n: float = 2.0,
        valve_s: float = 0.02,
        threshold: float = 0.3,
        supply: Callable[[], float] | None = None,
        rear: LimitSwitch | None = None,
        front: LimitSwitch | None = None,
        park: bool = False,
        doc: str = "",
        label_back: float = 48.0,
    ) -> None:
        n = math.hypot(*direction)
        if n == 0 or stroke <= 0:
            raise ValueError(f"piston {name}: needs a direction and a stroke > 0")
        self.name, self.valve = name, valve
        self.label_back = float(label_back)  # the name is written this far behind the retracted plate (mm)
        self.origin = (float(origin[0]), float(origin[1]))
        self.dir = (direction[0] / n, direction[1] / n)
        self.stroke = float(stroke)
        self.full = self.stroke if full is None else float(full)
        self.plate = (float(plate[0]), float(plate[1]))
        self._back = 0.5 * self.plate[1]  # from the plate's centre to its front face
        self.extend_speed, self.retract_speed = float(extend_speed), float(retract_speed)
        self.force, self.spring = force_n * NEWTON, spring_n * NEWTON
        self.valve_ns = round(valve_s * 1e9)
        self.threshold = float(threshold)
        self.supply = supply
        self.switches = [sw for sw in (rear, front) if sw is not None]
        self.park = park
        self.doc = doc
        self._sketch = Sketch(self._draw)

    # -- protocol -----------------------------------------------------------------------------
    def specs(self) -> list[SignalSpec]:
        out = [SignalSpec(self.valve, "actuator", doc=self.doc or f"valve of piston {self.name}: True = extend")]
        out += [SignalSpec(sw.name, "sensor", doc=sw.doc) for sw in self.switches]
        return out

    def subjects(self) -> set[str]:
        return {self.name}

    def reset(self, host: Host) -> bool:
        self.command = False
        self.open = False
        self.due_ns: int | None = None
        self.jammed = False
        self.s = 0.0
        self.at_front = False  # arrived at the full stroke, not yet backed off it by LEAVE mm
        self.at_rear = True
        self.reached = 0.0  # the farthest stroke since the valve last opened
        self._recheck = False  # an end switch was moved: update them even if the plate did not move
        body = pymunk.Body(MASS_KG, float("inf"))
        body.position = self._point(-0.5 * self.plate[1])
        w, t = self.plate
        dx, dy = self.dir
        nx, ny = -dy, dx
        corners = [
            (sx * nx * w / 2 + sy * dx * t / 2, sx * ny * w / 2 + sy * dy * t / 2)
            for sx, sy in ((-1, -1), (1, -1), (1, 1), (-1, 1))
        ]
        shape = pymunk.Poly(body, corners)
        shape.friction = 0.2
        shape.collision_type = CT_PLATE
        shape.filter = pymunk.ShapeFilter(categories=PLATE_CAT, mask=PART_CAT)
        a, b = self._point(-0.5 * t), self._point(self.stroke - 0.5 * t)
        groove = pymunk.GrooveJoint(host.space.static_body, body, a, b, (0.0, 0.0))
        host.space.add(body, shape, groove)
        self.body, self._shape, self._groove = body, shape, groove
        self._corners = corners
        self._stand_in: pymunk.Shape | None = None  # the static plate while parked
        self._h = chipmunk.handle(body)  # the per-step reads and writes go straight to Chipmunk
        for sw in self.switches:
            sw.reset()
            sw.update(0.0)
            host.sensors[sw.name] = sw.actuated
        if self.park:  # at rest retracted from the start
            self._park(host)
        return False

    def actuate(self, host: Host, signal: str, value: Any) -> bool:
        value = bool(value)
        if value == self.command:
            return False
        self.command = value
        self.due_ns = host.now_ns + self.valve_ns
        return True

    def jam(self, host: Host, jammed: bool = True) -> bool:
        """Fault: the rod is stuck where it is (a bent rod, a blocked guide)."""
        jammed = bool(jammed)
        if jammed and not self.jammed:
            host.emit("piston jammed", self.name, stroke_mm=round(self.s, 3))
        self.jammed = jammed
        return True

    def shift_cam(self, name: str, dx: float) -> None:
        """Fault: end switch ``name`` is mounted ``dx`` mm off its place along the stroke."""
        next(sw for sw in self.switches if sw.name == name).shift(dx)
        self._recheck = True

    def advance(self, host: Host, dt: float) -> bool:
        if self._stand_in is not None:
            self._unpark(host)
        if self.due_ns is not None and host.now_ns >= self.due_ns:
            self.open, self.due_ns = self.command, None
            if self.open:
                self.reached = 0.0
        h = self._h
        (ox, oy), (dx, dy) = self.origin, self.dir
        p, vel = chipmunk.get_position(h), chipmunk.get_velocity(h)
        s = (p.x - ox) * dx + (p.y - oy) * dy + self._back
        v = vel.x * dx + vel.y * dy
        if self.jammed:
            chipmunk.set_velocity(h, (0.0, 0.0))
            target = 0.0
        else:
            pressure = 1.0 if self.supply is None else self.supply()
            if self.open and pressure >= self.threshold:
                target, cap = self.extend_speed, self.force * pressure
            else:
                target, cap = -self.retract_speed, self.spring
            f = max(-cap, min(cap, MASS_KG * (target - v) / dt))
            chipmunk.set_force(h, (f * dx, f * dy))
        if s != self.s or s > self.reached or self._recheck:  # else _sense would change nothing
            self._sense(host, s)
        at_rest = s <= RETRACTED_WITHIN and target < 0 and abs(v) < 1e-3
        if at_rest:
            chipmunk.set_velocity(h, (0.0, 0.0))
        busy = not at_rest or self.open or self.due_ns is not None or self.jammed  # open: waiting for pressure
        if not busy and self.park:
            self._park(host)
        return busy

    def _park(self, host: Host) -> None:
        """At rest retracted: the body leaves the space, a static plate where it lies stands in for it."""
        p = chipmunk.get_position(self._h)
        stand_in = pymunk.Poly(host.space.static_body, [(p.x + cx, p.y + cy) for cx, cy in self._corners])
        shape = self._shape
        stand_in.friction, stand_in.collision_type, stand_in.filter = shape.friction, shape.collision_type, shape.filter
        host.space.remove(self.body, shape, self._groove)
        host.space.add(stand_in)
        self._stand_in = stand_in

    def _unpark(self, host: Host) -> None:
        """Woken: the body is back in the space where it rested, the stand-in goes."""
        host.space.remove(self._stand_in)
        host.space.add(self.body, self._shape, self._groove)
        self._stand_in = None

    def _sense(self, host: Host, s: float) -> None:
        moved = abs(s - self.s) > 1e-9 or self._recheck
        self.s, self._recheck = s, False
        self.reached = max(self.reached, s)
        if not self.at_front and s >= self.full - EXTENDED_WITHIN:
            self.at_front = True
            host.emit("piston extended", self.name, stroke_mm=round(s, 3))
        elif self.at_front and s < self.full - EXTENDED_WITHIN - LEAVE:
            self.at_front = False
        if not self.at_rear and s <= RETRACTED_WITHIN:
            self.at_rear = True
            host.emit("piston retracted", self.name, reached_mm=round(self.reached, 3))
        elif self.at_rear and s > RETRACTED_WITHIN + LEAVE:
            self.at_rear = False
        if moved:
            for sw in self.switches:
                if sw.update(s):
                    host.sensors[sw.name] = sw.actuated

    # -- drawing ------------------------------------------------------------------------------
    def _point(self, s: float) -> tuple[float, float]:
        return (self.origin[0] + s * self.dir[0], self.origin[1] + s * self.dir[1])

    def static_drawables(self) -> list[Drawable]:
        w, t = self.plate
        dx, dy = self.dir
        nx, ny = -dy, dx
        back = self._point(-t - 40.0)
        body = [
            (back[0] + nx * w * 0.3, back[1] + ny * w * 0.3),
            (back[0] - nx * w * 0.3, back[1] - ny * w * 0.3),
            (back[0] - nx * w * 0.3 + dx * 30, back[1] - ny * w * 0.3 + dy * 30),
            (back[0] + nx * w * 0.3 + dx * 30, back[1] + ny * w * 0.3 + dy * 30),
        ]
        label = self._point(-t - self.label_back)
        return [
            draw.polygon(f"pistons/{self.name}/cylinder", body, draw.FRAME, self.name),
            draw.label(f"pistons/{self.name}/label", label[0], label[1], self.name),
        ]

    def dynamic_drawables(self) -> list[Drawable]:
        return self._sketch((self.s, self.jammed, self.open))

    def _draw(self) -> list[Drawable]:
        w, t = self.plate
        dx, dy = self.dir
        nx, ny = -dy, dx
        face = self._point(self.s)
        rear = self._point(self.s - t)
        plate = [
            (face[0] + nx * w / 2, face[1] + ny * w / 2),
            (face[0] - nx * w / 2, face[1] - ny * w / 2),
            (rear[0] - nx * w / 2, rear[1] - ny * w / 2),
            (rear[0] + nx * w / 2, rear[1] + ny * w / 2),
        ]
        cyl = self._point(-t - 10.0)
        color = draw.PART_HELD if self.jammed else draw.BELT_RUNNING if self.open else draw.BELT
        return [
            draw.line(f"pistons/{self.name}/rod", [cyl, rear], draw.TEXT),
            draw.polygon(f"pistons/{self.name}/plate", plate, color, self.name),
        ]
