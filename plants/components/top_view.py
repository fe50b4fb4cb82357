"""The base of the top-view rigs (ALIGN, SORT): a table seen from above where parts slide with friction.

* **Space.** Top view, y up, mm/kg/s, no gravity, single-threaded; ``reset`` builds a fresh space in a fixed order.
* **Floor friction.** There is no normal force in a top view, so each part is tied to the table by the Chipmunk
  "top-down friction" pair (pymunk notes §2a): a ``PivotJoint`` with ``max_bias = 0`` and ``max_force = μ·m·g`` and
  a ``GearJoint`` with ``max_force = μ·m·g·r`` (r = (length + depth)/6, about the mean lever arm of a uniformly
  loaded rectangle). A pushed part slides and stops as on a real table.
* **Parts** are blocks ``length × depth`` (the :class:`~plants.components.workpiece.WorkpieceSpec`, seen from
  above). Spot sensors (:class:`SpotSensor`, a colour sensor), bins and a belt's edges are sensor zones
  (:func:`~plants.components.component.zone`, the :class:`~plants.components.component.ZoneSensor` protocol):
  pymunk's ``begin``/``separate`` call their owner's ``enter(host, part)`` / ``leave(host, part_id)``, which update
  the sensors (``part entered`` / ``part left`` events); nothing is queried per step.
* **Belts** carry parts by themselves: a placed part rests on the first component that claims the spot with
  ``carrier_at(x, y)`` (the :class:`~plants.components.component.Carrier` protocol; a
  :class:`~plants.components.top_belt.TopBelt`), else on the table.
* **Components** (piston, fence, sensors) plug in through :mod:`plants.components.component`; the rig steps the
  busy ones before each physics step.
* **C step.** The space is stepped with ``cpSpaceStep`` (:mod:`plants.components.chipmunk`), so nothing may add
  to or remove from it inside a step: the collision callbacks only change Python state, and a part that changes
  support (:meth:`TopViewPlant.support`, a part off the belt) gets its new joints after the step.
* **Still table, no physics.** After a step in which no part moves (speed < 1 µm/s) and no component is busy, the
  plant is quiescent and later steps only advance the clock, until something is actuated, placed or removed.
"""

from __future__ import annotations

import math
from collections.abc import Iterable
from dataclasses import replace
from typing import Any

import numpy as np
import pymunk

from plants.components import chipmunk, draw
from plants.components.collide import CT_BEAM, CT_PART, PART_CAT, STOP_CAT
from plants.components.component import Assembly, Carrier, Component, ZoneSensor, zone
from plants.components.sketch import Sketch
from plants.components.workpiece import WorkpieceSpec
from plcsim.plant import (
    OBSERVABLES,
    PARTS,
    QUIESCENCE,
    SENSOR_SHIFT,
    Drawable,
    PlantEvent,
    RigVerb,
    SignalSpec,
    Station,
)

G = 9810.0  # mm/s²
STILL_MM_S = 1e-3
LEADER = (170, 170, 175)  # the thin line from a sensor to its name written away from it


class TopPart:
    """A block on the table (top view)."""

    def __init__(self, pid: str, spec: WorkpieceSpec, x: float, y: float, angle: float, props: dict) -> None:
        self.id, self.spec, self.props = pid, spec, dict(props)
        mass = spec.mass_g / 1000.0
        self.body = pymunk.Body(mass, pymunk.moment_for_box(mass, (spec.length, spec.depth)))
        self.body.position = (x, y)
        self.body.angle = angle
        self.shape = pymunk.Poly.create_box(self.body, (spec.length, spec.depth))
        self.shape.friction = spec.friction
        self.shape.collision_type = CT_PART
        self.shape.filter = pymunk.ShapeFilter(categories=PART_CAT)
        self.shape.part = self
        self._h = chipmunk.handle(self.body)
        self.color = tuple(self.props.get("color", draw.PART))
        self._sketch = Sketch(lambda: [Drawable(f"parts/{pid}", "polygon", self.corners(), self.color, text=pid)])

    def drawable(self) -> Drawable:
        """The part drawn where it lies now."""
        h = self._h
        p = chipmunk.get_position(h)
        return self._sketch((p.x, p.y, chipmunk.get_angle(h)))[0]

    def corners(self) -> np.ndarray:
        """The four corners in world coordinates, (4, 2) (:func:`~plants.components.draw.box`: no BLAS)."""
        h = self._h
        p = chipmunk.get_position(h)
        return draw.box(p.x, p.y, chipmunk.get_angle(h), self.spec.length / 2, self.spec.depth / 2)


class SpotSensor:
    """A reflex or through-beam sensor seen from above: True while a part covers its spot (a circle).

    ``sees``: the part property it detects (an inspection sensor, ``sees="bad"``): it is True only while a part whose
    property is truthy covers the spot, and the others pass unseen (no event either). Default: every part.
    """

    EVENTS = frozenset({"part entered", "part left"})

    def __init__(
        self, name: str, x: float, y: float, radius: float = 3.0, doc: str = "", *, sees: str | None = None
    ) -> None:
        self.name, self.x, self.y, self.radius, self.doc = name, float(x), float(y), float(radius), doc
        self.sees = sees
        self._sketch = Sketch(self._draw)

    def specs(self) -> list[SignalSpec]:
        return [SignalSpec(self.name, "sensor", doc=self.doc or f"spot at ({self.x:g}, {self.y:g}): True when covered")]

    def subjects(self) -> set[str]:
        return {self.name}

    def reset(self, host: Any) -> bool:
        self.parts: dict[str, None] = {}
        self.dx = 0.0
        self._attach(host)
        host.sensors[self.name] = False
        return False

    def _attach(self, host: Any) -> None:
        self.shape = zone(host, self, self._sensing_shape(host.space.static_body))

    def _sensing_shape(self, body: pymunk.Body) -> pymunk.Shape:
        """The sensor's area: a spot of ``radius`` (a :class:`Beam` is a line across the belt)."""
        return pymunk.Circle(body, self.radius, (self.x + self.dx, self.y))

    def enter(self, host: Any, part: TopPart) -> None:
        pid = part.id
        if self.sees is not None and not part.props.get(self.sees):
            return
        if pid not in self.parts:
            self.parts[pid] = None
            host.sensors[self.name] = True
            host.emit("part entered", self.name, pid)

    def leave(self, host: Any, pid: str) -> None:
        if pid in self.parts:
            del self.parts[pid]
            host.sensors[self.name] = bool(self.parts)
            host.emit("part left", self.name, pid)

    def actuate(self, host: Any, signal: str, value: Any) -> bool:
        return False

    def advance(self, host: Any, dt: float) -> bool:
        return False

    def static_drawables(self) -> list[Drawable]:
        return [draw.label(f"sensors/{self.name}/label", self.x + self.radius + 2, self.y + 4, self.name)]

    def dynamic_drawables(self) -> list[Drawable]:
        return self._sketch((bool(self.parts), self.dx))

    def _draw(self) -> list[Drawable]:
        color = draw.BEAM_CUT if self.parts else draw.BEAM_FREE
        return [draw.circle(f"sensors/{self.name}", self.x + self.dx, self.y, self.radius, color, self.name)]


class Beam(SpotSensor):
    """A light barrier across a belt seen from above: True while a part interrupts the line x, y0..y1."""

    def __init__(
        self,
        name: str,
        x: float,
        y0: float,
        y1: float,
        *,
        width: float = 2.0,
        doc: str = "",
        label_y: float | None = None,
    ) -> None:
        super().__init__(name, x, 0.5 * (y0 + y1), 0.5 * width, doc or f"light barrier at x = {x:g} mm")
        self.y0, self.y1 = float(y0), float(y1)
        self.label_y = label_y  # the name's height (default just past the beam's end), joined to the beam by a line

    def _sensing_shape(self, body: pymunk.Body) -> pymunk.Shape:
        x, hw = self.x + self.dx, self.radius
        return pymunk.Poly(body, [(x - hw, self.y0), (x + hw, self.y0), (x + hw, self.y1), (x - hw, self.y1)])

    def static_drawables(self) -> list[Drawable]:
        if self.label_y is None:
            return [draw.label(f"sensors/{self.name}/label", self.x, self.y1 + 6.0, self.name)]
        leader = draw.line(f"sensors/{self.name}/leader", [(self.x, self.y1 + 4.0), (self.x, self.label_y)], LEADER)
        return [leader, draw.label(f"sensors/{self.name}/label", self.x, self.label_y, self.name)]

    def _draw(self) -> list[Drawable]:
        color = draw.BEAM_CUT if self.parts else draw.BEAM_FREE
        x = self.x + self.dx
        return [draw.line(f"sensors/{self.name}", [(x, self.y0 - 4.0), (x, self.y1 + 4.0)], color, self.name)]


class Fence:
    """A fixed straight fence (a static segment) parts are pushed against."""

    EVENTS: frozenset[str] = frozenset()

    def __init__(self, name: str, a: tuple[float, float], b: tuple[float, float], *, thickness: float = 4.0) -> None:
        self.name, self.a, self.b, self.thickness = name, a, b, float(thickness)

    def specs(self) -> list[SignalSpec]:
        return []

    def subjects(self) -> set[str]:
        return set()

    def reset(self, host: Any) -> bool:
        r = self.thickness / 2
        (ax, ay), (bx, by) = self.a, self.b
        seg = pymunk.Segment(host.space.static_body, (ax, ay - r), (bx, by - r), r)  # its face on the a-b line
        seg.friction = 0.2
        seg.filter = pymunk.ShapeFilter(categories=STOP_CAT)
        host.space.add(seg)
        return False

    def actuate(self, host: Any, signal: str, value: Any) -> bool:
        return False

    def advance(self, host: Any, dt: float) -> bool:
        return False

    def static_drawables(self) -> list[Drawable]:
        (ax, ay), (bx, by) = self.a, self.b
        t = self.thickness
        return [draw.polygon(f"frame/{self.name}", [(ax, ay - t), (bx, by - t), (bx, by), (ax, ay)], draw.END_STOP)]

    def dynamic_drawables(self) -> list[Drawable]:
        return []


class TopViewPlant:
    """Base class of the top-view rigs (see the module docstring).

    Args:
        name: plant name.
        components: the rig's pieces (pistons, fences, spot sensors ...).
        stations: where parts are placed and taken from.
        table: (xmin, ymin, xmax, ymax) of the table (mm), drawn and used as the bounds.
        workpiece: the parts' size and mass.
        friction: floor/part μ.
    """

    view = "top"
    CAPABILITIES = frozenset({PARTS, QUIESCENCE, SENSOR_SHIFT, OBSERVABLES})
    VERBS: dict[str, RigVerb] = {}
    PART_PROPERTIES: dict[str, str] = {"color": "the part's colour as drawn: (r, g, b), 0..255"}
    """The properties a scenario may give a part (a rig adds to a copy of it)."""
    PART_EVENTS = frozenset({"part placed", "part removed"})

    def __init__(
        self,
        name: str,
        *,
        components: Iterable[Component],
        stations: Iterable[Station],
        table: tuple[float, float, float, float],
        workpiece: WorkpieceSpec,
        friction: float = 0.3,
        seed: int = 0,
    ) -> None:
        self.name = name
        self.assembly = Assembly(components)
        self.EVENTS = self.PART_EVENTS | self.assembly.events
        self.stations = {s.name: s for s in stations}
        self.table = table
        self.workpiece = workpiece
        self.friction = float(friction)
        self.signals: dict[str, SignalSpec] = {s.name: s for s in self.assembly.specs()}
        self.sensors: dict[str, Any] = {}
        self.events: list[PlantEvent] = []
        self.seed = seed
        self.reset(seed=seed)

    def event_subjects(self) -> set[str]:
        return set(self.stations) | self.assembly.subjects()

    # -- host of the components ---------------------------------------------------------------
    def emit(self, kind: str, subject: str, part: str | None = None, **data: Any) -> None:
        """Record a plant event at the current time."""
        self.events.append(PlantEvent(self.now_ns, kind, subject, part, data))

    def wake(self, component: Component) -> None:
        self.assembly.wake(component)
        self._still = False

    # -- lifecycle ----------------------------------------------------------------------------
    def reset(self, *, seed: int | None = None) -> None:
        if seed is not None:
            self.seed = seed
        self.rng = np.random.default_rng(self.seed)
        self.now_ns = 0
        self.events.clear()
        self.sensors.clear()
        old = getattr(self, "space", None)
        if old is not None:  # a freed space calls `separate` for its contacts: keep them away from the new state
            old.on_collision(CT_PART, CT_BEAM, begin=pymunk.empty_callback, separate=pymunk.empty_callback)
        self.space = pymunk.Space()
        self.space.iterations = 10
        self.space.on_collision(CT_PART, CT_BEAM, begin=self._spot_begin, separate=self._spot_separate)
        self.parts: dict[str, TopPart] = {}
        self.retired: dict[str, Drawable] = {}  # parts out of play (in a bin): drawn where they lie, not simulated
        self._joints: dict[str, tuple] = {}
        self._next_id = 1
        self._still = True
        self._stepping = False
        self._resupport: list[tuple[str, pymunk.Body]] = []  # parts that changed support during a step
        self._cp_step, self._cp_space = chipmunk.stepper(self.space)
        self._fresh = True  # a body was added: pymunk's own step checks it once
        self.assembly.reset(self)
        self._check_zones()

    def _check_zones(self) -> None:
        """Refuse a sensor shape the collision callbacks could not report to (made without :func:`zone`)."""
        for shape in self.space.shapes:
            if shape.collision_type == CT_BEAM and not isinstance(getattr(shape, "owner", None), ZoneSensor):
                owner = getattr(shape, "owner", None)
                what = "no owner" if owner is None else f"the owner {type(owner).__name__}, which lacks enter/leave"
                raise TypeError(
                    f"{self.name}: a sensor zone in the space has {what}; make sensor zones with "
                    f"plants.components.zone(host, owner, shape), the owner having enter(host, part) and "
                    f"leave(host, part_id) (the ZoneSensor protocol)"
                )

    def quiescent(self) -> bool:
        """True when nothing moves and no component is busy: a step only advances the clock."""
        return self._still and not self.assembly.busy

    def actuate(self, name: str, value: Any) -> None:
        if not self.assembly.owns(name):
            actuators = [n for n, s in self.signals.items() if s.direction == "actuator"]
            raise KeyError(f"{self.name} has no actuator {name!r} (actuators: {actuators})")
        self.assembly.actuate(self, name, value)
        self._still = False

    def step(self, dt_ns: int) -> None:
        if dt_ns <= 0:
            raise ValueError(f"step: dt_ns must be > 0, not {dt_ns}")
        self.now_ns += dt_ns
        assembly = self.assembly
        if self._still and not assembly.busy:  # quiescent
            return
        dt = dt_ns / 1e9
        if assembly.busy:
            assembly.advance(self, dt)
        self._stepping = True
        if self._fresh:
            self._fresh = False
            self.space.step(dt)
        else:  # the C step: nothing changes the space inside it (see support), so pymunk's bookkeeping is not needed
            self._cp_step(self._cp_space, dt)
        self._stepping = False
        if self._resupport:
            resupport, self._resupport = self._resupport, []
            for pid, body in resupport:
                self.support(pid, body)
        self._still = not assembly.busy and self._parts_still()

    def _parts_still(self) -> bool:
        """Whether no part moves (slower than 1 µm/s, turning slower than 10 µrad/s)."""
        for p in self.parts.values():
            v = chipmunk.get_velocity(p._h)
            if not (math.sqrt(v.x**2 + v.y**2) < STILL_MM_S and abs(chipmunk.get_angular_velocity(p._h)) < 1e-5):
                return False  # (Vec2d.length, as pymunk computes it)
        return True

    # -- parts --------------------------------------------------------------------------------
    def pose_at(self, station: Station, offset_mm: float, angle_deg: float) -> tuple[float, float, float]:
        """Where a part placed at ``station`` lies: (x, y, angle rad); here ``offset_mm`` is along x."""
        return (station.x + offset_mm, station.y, math.radians(angle_deg))

    def place(
        self,
        station: str,
        *,
        part: str | None = None,
        offset_mm: float = 0.0,
        angle_deg: float = 0.0,
        **properties: Any,
    ) -> str:
        """Put a new part at ``station`` (pose: :meth:`pose_at`); ``color=(r, g, b)`` is kept for drawing."""
        st = self._station(station)
        if part is None:
            while f"p{self._next_id}" in self.parts:
                self._next_id += 1
            part, self._next_id = f"p{self._next_id}", self._next_id + 1
        elif part in self.parts:
            raise ValueError(f"{self.name}: a part named {part!r} is already in the plant")
        spec = properties.pop("spec", self.workpiece)
        x, y, a = self.pose_at(st, float(offset_mm), float(angle_deg))
        p = TopPart(part, spec, x, y, a, properties)
        bb = p.shape.cache_bb()
        for other in self.parts.values():
            if bb.intersects(other.shape.bb):  # the bounding boxes: an operator keeps a hand's width apart
                raise ValueError(f"{self.name}: cannot place {part} at {station}: part {other.id} is there")
        self.space.add(p.body, p.shape)
        self._fresh = True
        self.parts[part] = p
        self._tie(p, self.support_at(x, y))
        self._still = False
        data = {"x": x, "y": y, "angle_deg": float(angle_deg), "offset_mm": float(offset_mm)}
        data.update({k: v for k, v in properties.items() if isinstance(v, int | float | str)})
        self.emit("part placed", station, part, **data)
        return part

    def support_at(self, x: float, y: float) -> pymunk.Body:
        """The body a part placed at (x, y) rests on: the first carrier's that claims it (a belt), else the table's."""
        for c in self.assembly.components:
            if isinstance(c, Carrier):
                body = c.carrier_at(x, y)
                if body is not None:
                    return body
        return self.space.static_body

    def support(self, pid: str, body: pymunk.Body) -> None:
        """Part ``pid`` now rests on ``body`` (it slid off a belt onto the table); called inside a step (a collision
        callback), the joints change after it."""
        if self._stepping:
            self._resupport.append((pid, body))
            return
        p = self.parts.get(pid)
        if p is not None:
            self.space.remove(*self._joints.pop(pid))
            self._tie(p, body)

    def _tie(self, p: TopPart, body: pymunk.Body) -> None:
        """The friction joints between a part and what it rests on."""
        mass, spec = p.spec.mass_g / 1000.0, p.spec
        pivot = pymunk.PivotJoint(body, p.body, tuple(p.body.position))
        pivot.max_bias, pivot.max_force = 0.0, self.friction * mass * G
        gear = pymunk.GearJoint(body, p.body, 0.0, 1.0)
        gear.max_bias, gear.max_force = 0.0, self.friction * mass * G * (spec.length + spec.depth) / 6.0
        self.space.add(pivot, gear)
        self._joints[p.id] = (pivot, gear)

    def remove(self, target: str) -> None:
        """Take a part away (by id, or the part nearest the station)."""
        p = self._resolve(target)
        subject = target if target in self.stations else self._nearest_station(p)
        self.emit("part removed", subject, p.id, **self.measure_part(p))
        for comp in self.assembly.components:
            leave = getattr(comp, "leave", None)
            if leave is not None:
                leave(self, p.id)
        p.shape.part = None
        self.space.remove(p.shape, p.body, *self._joints.pop(p.id))
        del self.parts[p.id]
        self._still = False

    def retire(self, pid: str) -> None:
        """Take part ``pid`` out of the physics where it lies (it is done: in a bin); it is still drawn there."""
        p = self.parts.pop(pid)
        self.retired[pid] = replace(p.drawable(), text="")  # unnamed: names of parts piled in a bin overlap
        p.shape.part = None
        self.space.remove(p.shape, p.body, *self._joints.pop(pid))
        self._still = False

    def measure_part(self, p: TopPart) -> dict[str, float]:
        """The rig's measurement of a part (its pose here); a rig adds what its task grades."""
        x, y = p.body.position
        return {"x": round(x, 3), "y": round(y, 3), "angle_deg": round(math.degrees(p.body.angle), 3)}

    def shift_sensor(self, name: str, dx_mm: float) -> None:
        """Fault: a spot sensor or a component's switch is mounted ``dx_mm`` off its place."""
        comp = self.assembly.owner.get(name)
        if isinstance(comp, SpotSensor):
            comp.dx = float(dx_mm)
            self.space.remove(comp.shape)
            comp._attach(self)
            self._still = False
            return
        if comp is None:
            raise KeyError(f"{self.name} has no sensor {name!r}")
        self.assembly.shift(self, name, dx_mm)
        self._still = False

    def _station(self, name: str) -> Station:
        try:
            return self.stations[name]
        except KeyError:
            raise KeyError(f"{self.name} has no station {name!r} (stations: {list(self.stations)})") from None

    def _nearest_station(self, p: TopPart) -> str:
        x, y = p.body.position
        return min(self.stations.values(), key=lambda s: math.hypot(s.x - x, s.y - y)).name

    def _resolve(self, target: str) -> TopPart:
        if target in self.parts:
            return self.parts[target]
        st = self._station(target)
        near = [p for p in self.parts.values() if math.hypot(p.body.position.x - st.x, p.body.position.y - st.y) < 80]
        if not near:
            raise KeyError(f"{self.name}: no part at {target!r}")
        return min(near, key=lambda p: math.hypot(p.body.position.x - st.x, p.body.position.y - st.y))

    def _spot_begin(self, arbiter: pymunk.Arbiter, space: pymunk.Space, data: Any) -> None:
        ps, ss = arbiter.shapes
        if ps.part is not None:
            ss.owner.enter(self, ps.part)

    def _spot_separate(self, arbiter: pymunk.Arbiter, space: pymunk.Space, data: Any) -> None:
        ps, ss = arbiter.shapes
        part, owner = getattr(ps, "part", None), getattr(ss, "owner", None)
        if part is not None and owner is not None:
            owner.leave(self, part.id)

    # -- observation and drawing --------------------------------------------------------------
    def observables(self) -> dict[str, float]:
        return {"parts": float(len(self.parts))}

    def bounds(self) -> tuple[float, float, float, float]:
        x0, y0, x1, y1 = self.table
        return (x0 - 10.0, y0 - 10.0, x1 + 10.0, y1 + 10.0)

    def static_drawables(self) -> list[Drawable]:
        x0, y0, x1, y1 = self.table
        table = draw.polygon("frame/table", draw.rect(x0, y0, x1, y1), (225, 225, 228))
        return [table, *self.assembly.static_drawables()]

    def dynamic_drawables(self) -> list[Drawable]:
        parts = [p.drawable() for p in self.parts.values()]
        return [*self.retired.values(), *parts, *self.assembly.dynamic_drawables()]
