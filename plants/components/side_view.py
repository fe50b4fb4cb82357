"""The side-view belt rigs' base: a pymunk space, parts and operator actions, and the rig's components.

A rig (``plants.conveyors``, ``plants.punch``) is an assembly of components on the protocol of
:mod:`plants.components.component`: belts (:class:`~plants.components.belt.Belt`), light barriers
(:class:`~plants.components.light_barrier.LightBarrier`), the frame's end stops and dead plates
(:mod:`plants.components.frame`), an operator panel, a press, an axis. :class:`SideViewPlant` implements the
:class:`plcsim.plant.Plant` protocol for them: it owns the space, the parts and the clock, adds up the components'
signals, events, subjects and drawings, routes each actuator command and fault to the component that owns it, and
steps only the busy ones. It knows no component kind; what it asks of them beyond the protocol is optional:

* ``carries_parts`` (True on a belt): parts are placed on it and located by it (``contains(x)``, ``top``, ``x0``,
  ``x1``); the fall zone lies 25 mm under the lowest one;
* ``enter(host, part)`` / ``leave(host, part)``: a shape of the component with ``shape.owner = component`` and
  collision type ``CT_BEAM`` (a sensor) or ``CT_STOP`` (a solid stop) began or ended touching a part;
* ``part_gone(host, part_id)``: a part left the plant (removed, fallen or knocked off);
* ``commit(host)``: called at the start of the next step after ``host.defer(component)`` (the relays of one
  scan taken together); ``settle(host)``: called after the physics step that follows ``host.after_step(component)``;
* ``jam(host, jammed, subject)``, ``shift_sensor(host, name, dx)`` or ``shift_cam(name, dx)``, ``operate(host, name,
  value)``: the faults and the operator; ``CAPABILITIES``: what the component adds to the rig (a panel: operator);
* ``layer = "under"``: drawn under the parts (belts, the frame); the rest is drawn over them (beams, press, panel).

* **Space.** Side view, y up, mm/kg/s, gravity 9810 mm/s², default ``collision_slop`` (0.1 mm) and 10 iterations,
  single-threaded (a threaded space is not deterministic). ``reset`` builds a fresh space in a fixed order (the
  components under the parts, then the others, each in the rig's order; then the fall zone), so the same actions give
  bit-identical positions in any process.
* **Event-driven sensors.** Beams are sensor shapes; pymunk's ``begin``/``separate`` callbacks reach the beam's
  ``enter``/``leave``, which update the live ``sensors`` dict and append ``part entered`` / ``part left`` events.
  Nothing is queried per step.
* **Actuators on change only.** A motor command sets a belt's target speed at the next step; the belt is a busy
  component and writes its ``surface_velocity`` each step only until it has settled (≈ 0.6 s after a change).
* **Fell off.** A sensor zone below the belts (its top 25 mm under the lowest belt surface) catches every part that
  drops off an end or is knocked off; the part is removed after the step with a ``part fell off`` event.
* **No parts, no physics.** With no part in the space, ``step`` only advances the clock and the busy components
  (the hours-meter exercises run for simulated hours with an empty belt).

Per step the cost is one ``space.step`` plus a few attribute reads; see ``plants/conveyors.py`` for measured figures.
Events are stamped with the time at the **end** of the step in which they happened (``now_ns`` after the step); a
command taken at the start of a step (``commit``) is stamped with the step's start, when the outputs changed.
A placement takes effect at once, but beams see a newly placed part from the next physics step on (the same 1-step
latency as any other physical change).
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Mapping
from typing import Any

import numpy as np
import pymunk

from plants.components import chipmunk, draw
from plants.components.belt import Belt
from plants.components.collide import CT_BEAM, CT_FALL, CT_PART, CT_STOP, FALL_CAT
from plants.components.component import Assembly, Component
from plants.components.frame import DeadPlate, EndStop
from plants.components.light_barrier import LightBarrier
from plants.components.workpiece import STANDARD, Part, WorkpieceSpec
from plcsim.plant import (
    MOTOR_JAM,
    OBSERVABLES,
    PART_FAULTS,
    PARTS,
    QUIESCENCE,
    SENSOR_SHIFT,
    Drawable,
    PlantEvent,
    RigVerb,
    SignalSpec,
    Station,
)

GRAVITY = 9810.0  # mm/s²

__all__ = ["DeadPlate", "EndStop", "SideViewPlant", "StationOccupiedError"]


class StationOccupiedError(ValueError):
    """``place`` found another part where the new one would go (the operator cannot put a part there)."""


class SideViewPlant:
    """Base class of the side-view belt rigs (see the module docstring).

    Args:
        name: plant name (``CONV1``).
        components: the rig's components, in the order their signals are listed (belts upstream first among
            themselves); at least one belt.
        stations: named places for ``place``/``remove``; ``belt_stations`` maps the ones that mean "a belt" (the
            station is the belt's upstream end and ``offset_mm`` is the position along it) to their belt.
        workpiece: the parts placed without a ``spec``.
        seed: initial seed (the belt rigs have no randomness of their own; ``rng`` is offered to components).
        max_step_ns: a ``step`` longer than this is split into equal sub-steps (physics stays stable at coarse scans).
    """

    view = "side"
    EVENTS: frozenset[str] = frozenset(
        {"part placed", "part removed", "part fell off", "part jammed", "part released", "part knocked off"}
    )
    """The kinds of event the base emits; a rig's ``EVENTS`` adds its components' kinds."""
    CAPABILITIES = frozenset({PARTS, PART_FAULTS, QUIESCENCE, SENSOR_SHIFT, MOTOR_JAM, OBSERVABLES})
    """What the rig offers besides the core (its components may add more: a panel, the operator)."""
    VERBS: dict[str, RigVerb] = {}
    """The rig's own scenario verbs (a subclass adds to a copy of it)."""
    PART_PROPERTIES: dict[str, str] = {"color": "the part's colour as drawn: (r, g, b), 0..255"}
    """The properties a scenario may give a part (a rig adds to a copy of it)."""

    def __init__(
        self,
        name: str,
        *,
        components: Iterable[Component],
        stations: Iterable[Station],
        belt_stations: Mapping[str, Belt] | None = None,
        workpiece: WorkpieceSpec = STANDARD,
        seed: int = 0,
        max_step_ns: int = 5_000_000,
    ) -> None:
        self.name = name
        self.assembly = Assembly(components)
        comps = self.assembly.components
        self.belts: list[Belt] = [c for c in comps if getattr(c, "carries_parts", False)]
        if not self.belts:
            raise ValueError(f"{name}: a side-view rig needs a belt (a component that carries parts)")
        self._under = [c for c in comps if getattr(c, "layer", "") == "under"]
        self._over = [c for c in comps if getattr(c, "layer", "") != "under"]
        self._gone_hooks = [c for c in comps if hasattr(c, "part_gone")]
        self.barriers: list[LightBarrier] = [c for c in comps if isinstance(c, LightBarrier)]
        self.barrier = {b.name: b for b in self.barriers}  # for a rig's own use and tests; the base needs none
        self.panel = next((c for c in comps if hasattr(c, "operate")), None)
        self.EVENTS = self.EVENTS | self.assembly.events
        self.CAPABILITIES = self.CAPABILITIES.union(*(getattr(c, "CAPABILITIES", ()) for c in comps))
        self.workpiece = workpiece
        self.max_step_ns = int(max_step_ns)
        self.stations: dict[str, Station] = {s.name: s for s in stations}
        self.belt_stations = dict(belt_stations or {})
        self._belt_by_name = {b.name: b for b in self.belts}
        self.signals: dict[str, SignalSpec] = {s.name: s for s in self.assembly.specs()}
        self.sensors: dict[str, Any] = {}
        self.events: list[PlantEvent] = []
        self.seed = seed
        self.reset(seed=seed)

    def event_subjects(self) -> set[str]:
        """Every ``subject`` its events can name: the stations and the components' names (beams, belts, motors ...)."""
        return set(self.stations) | self.assembly.subjects()

    # --- what a component sees of the rig (plants.components.component.Host) ---------------------------------
    def emit(self, kind: str, subject: str, part: str | None = None, **data: Any) -> None:
        """Record a plant event at the current time."""
        self.events.append(PlantEvent(self.now_ns, kind, subject, part, data))

    def wake(self, component: Component) -> None:
        """Step ``component`` from the next step on."""
        self.assembly.wake(component)

    def defer(self, component: Component) -> None:
        """Call ``component.commit(self)`` at the start of the next step (before the clock advances)."""
        if component not in self._deferred:
            self._deferred.append(component)

    def after_step(self, component: Component) -> None:
        """Call ``component.settle(self)`` after the next physics step (at once if there is none: no parts)."""
        if not self._live:
            component.settle(self)
        elif component not in self._settle:
            self._settle.append(component)
            self._post = True

    # --- protocol: lifecycle ---------------------------------------------------------------------------------
    def reset(self, *, seed: int | None = None) -> None:
        """Back to the initial state: a new space, no parts, motors off, faults cleared, time 0."""
        if seed is not None:
            self.seed = seed
        self.rng = np.random.default_rng(self.seed)
        self.now_ns = 0
        self.events.clear()  # the same list and dict objects: the wiring may hold references to them
        self.sensors.clear()
        old = getattr(self, "space", None)
        if old is not None:  # a freed space calls `separate` for its contacts: keep them away from the new state
            for pair in ((CT_PART, CT_BEAM), (CT_PART, CT_STOP), (CT_PART, CT_FALL)):
                old.on_collision(*pair, begin=pymunk.empty_callback, separate=pymunk.empty_callback)
        space = pymunk.Space()
        space.gravity = (0.0, -GRAVITY)
        space.iterations = 10
        self.space = space
        self._live = 0  # parts in the space
        self._deferred: list[Component] = []
        self._settle: list[Component] = []
        self._post = False
        self.assembly.busy = []
        for c in self._under + self._over:
            if c.reset(self):
                self.wake(c)
        lo = min(b.top for b in self.belts) - 25.0
        xmin, _, xmax, _ = self.bounds()
        self.fall_top = lo
        fall = pymunk.Poly(
            space.static_body, [(xmin - 2000, -20000), (xmax + 2000, -20000), (xmax + 2000, lo), (xmin - 2000, lo)]
        )
        fall.sensor = True
        fall.collision_type = CT_FALL
        fall.filter = pymunk.ShapeFilter(categories=FALL_CAT)
        space.add(fall)
        for ct in (CT_BEAM, CT_STOP):
            space.on_collision(CT_PART, ct, begin=self._touch_begin, separate=self._touch_separate)
        space.on_collision(CT_PART, CT_FALL, begin=self._fall_begin)
        # pymunk's Space.step wraps cpSpaceStep in bookkeeping for adding/removing objects inside callbacks (which
        # this plant never does: it defers removals to after the step) and costs 0.8 µs more than the physics of a
        # one-part belt. The plant calls the C step directly except in the step right after a body was added.
        self._cp_step, self._cp_space = chipmunk.stepper(space)
        self._fresh = False
        self.parts: dict[str, Part] = {}
        self._next_id = 1
        self._falling: list[Part] = []

    def quiescent(self) -> bool:
        """True when a step would only advance the clock: no part in the plant and every drive settled.

        A quiescent plant may be stepped by any ``dt_ns`` at once; the simulator uses this to skip
        the steps of an idle machine (an hours meter counting a belt that runs empty).
        """
        return not self._live and not self.assembly.busy and not self._deferred

    def step(self, dt_ns: int) -> None:
        """Advance by ``dt_ns``: the commands of the last scan, the busy components, then one physics step (skipped
        with no parts)."""
        busy = self.assembly.busy  # the list wake() appends to (advance() replaces it)
        if not self._live and not busy and not self._deferred and dt_ns > 0:
            self.now_ns += dt_ns
            return
        if dt_ns > self.max_step_ns or dt_ns <= 0:
            self._step_split(dt_ns)
            return
        if self._deferred:
            self._commit()
        self.now_ns += dt_ns
        dt = dt_ns / 1e9
        if busy:
            self.assembly.advance(self, dt)
        if self._live:
            if self._fresh:  # a body was added: pymunk's own step checks it once
                self._fresh = False
                self.space.step(dt)
            else:
                self._cp_step(self._cp_space, dt)
            if self._post:
                self._after_step()

    def _commit(self) -> None:
        deferred, self._deferred = self._deferred, []
        for c in deferred:
            if c.commit(self):
                self.wake(c)

    def _step_split(self, dt_ns: int) -> None:
        dt_ns = int(dt_ns)
        if dt_ns <= 0:
            raise ValueError(f"step: dt_ns must be > 0, not {dt_ns}")
        n = -(-dt_ns // self.max_step_ns)
        base, rem = divmod(dt_ns, n)
        for k in range(n):
            self.step(base + (1 if k < rem else 0))

    def _after_step(self) -> None:
        self._post = False
        if self._falling:
            falling, self._falling = self._falling, []
            for part in falling:
                if part.state != "gone":
                    self._drop(part, "part fell off", self._locate(part.x), {"x": part.x})
        if self._settle:
            settle, self._settle = self._settle, []
            for c in settle:
                c.settle(self)

    # --- protocol: actuators and operator ----------------------------------------------------------------------
    def actuate(self, name: str, value: Any) -> None:
        """A PLC output changed: its component takes it (a motor relay at the next step, a lamp at once)."""
        if not self.assembly.owns(name):
            raise KeyError(f"{self.name} has no actuator {name!r} (actuators: {self._actuator_names()})")
        self.assembly.actuate(self, name, value)

    def _actuator_names(self) -> list[str]:
        return [n for n, s in self.signals.items() if s.direction == "actuator"]

    def operate(self, name: str, value: Any) -> None:
        """The operator sets a button or switch on the rig's panel."""
        c = self.assembly.owner.get(name)
        if c is None or not hasattr(c, "operate"):
            if self.panel is None:
                raise KeyError(f"{self.name} has no operator controls (a panel was not configured)")
            c = self.panel
        c.operate(self, name, value)

    # --- faults --------------------------------------------------------------------------------------------------
    def shift_sensor(self, name: str, dx_mm: float) -> None:
        """Fault: the sensor ``name`` (a light barrier, a component's cam) is mounted ``dx_mm`` off its nominal place
        (absolute, not cumulative); its component says when it sees the parts again."""
        c = self.assembly.owner.get(name)
        if c is None or name not in self.signals or self.signals[name].direction != "sensor":
            raise KeyError(f"{self.name} has no sensor {name!r} to shift")
        if hasattr(c, "shift_sensor"):
            c.shift_sensor(self, name, dx_mm)
        else:
            self.assembly.shift(self, name, dx_mm)

    def jam_motor(self, name: str, jammed: bool = True) -> None:
        """Fault: the motor (actuator name, or belt name) is blocked: commanded or not, its belt does not move.
        The drive of another component (an axis, by its name or an actuator of it) is jammed by its component."""
        c = self._belt_by_name.get(name) or self.assembly.owner.get(name)
        if c in self.belts:
            if c.jam(self, jammed, name):
                self.wake(c)
            return
        if not self.assembly.has(name):
            raise KeyError(f"{self.name} has no motor or belt {name!r} (motors: {self._motor_names()})")
        self.assembly.jam(self, name, jammed)

    def _motor_names(self) -> list[str]:
        return [a for b in self.belts for a in b.actuators]

    # --- protocol: parts -------------------------------------------------------------------------------------------
    def place(
        self,
        station: str,
        *,
        part: str | None = None,
        offset_mm: float = 0.0,
        angle_deg: float = 0.0,
        **properties: Any,
    ) -> str:
        """Put a new workpiece at ``station`` (its centre at station x + ``offset_mm``, turned by ``angle_deg``).

        The part is dropped so that its lowest corner is 0.01 mm above the belt under it. Properties are kept with
        the part (``color=(r, g, b)`` is used for drawing; ``spec=WorkpieceSpec(...)`` changes its size).
        Raises :class:`StationOccupiedError` if another part lies where the new one would go.
        """
        st = self._get_station(station)
        x = st.x + float(offset_mm)
        belt = self._support(x)
        spec = properties.pop("spec", self.workpiece)
        for other in self.parts.values():
            if (
                other.state in ("on", "held")
                and abs(other.x - x) < 0.5 * (spec.length + other.spec.length) - 1e-6
                and other.body.position.y < belt.top + spec.height + other.spec.height
            ):
                raise StationOccupiedError(
                    f"{self.name}: cannot place a part at {station} (x = {x:.1f} mm): "
                    f"part {other.id} is there (x = {other.x:.1f} mm)"
                )
        if part is None:
            while f"p{self._next_id}" in self.parts:
                self._next_id += 1
            part = f"p{self._next_id}"
            self._next_id += 1
        elif part in self.parts:
            raise ValueError(f"{self.name}: a part named {part!r} is already in the plant")
        ang = math.radians(float(angle_deg))
        y = belt.top + spec.rest_height(ang) + 0.01
        p = Part.create(part, spec, x, y, ang, self.now_ns, properties)
        self.space.add(p.body, p.shape)
        self._fresh = True
        self.parts[part] = p
        self._live += 1
        data = {"x": x, "angle_deg": float(angle_deg)}
        data.update(properties)
        self.events.append(PlantEvent(self.now_ns, "part placed", station, part, data))
        return part

    def remove(self, target: str) -> None:
        """Take a part away (by id, or the part at a station)."""
        p = self._resolve(target, states=("on", "held", "off"))
        self._drop(p, "part removed", target if target in self.stations else self._locate(p.x), {"x": p.x})

    def hold(self, target: str) -> None:
        """Jam a part: a pin joint holds it where it is (the belt slips under it) until :meth:`release`."""
        p = self._resolve(target, states=("on", "held"))
        if p.state == "held":
            return
        body = p.body
        pin = pymunk.PivotJoint(self.space.static_body, body, tuple(body.position))
        turn = pymunk.RotaryLimitJoint(self.space.static_body, body, body.angle, body.angle)
        self.space.add(pin, turn)
        p.joints = (pin, turn)
        p.state = "held"
        self.events.append(PlantEvent(self.now_ns, "part jammed", self._locate(p.x), p.id, {"x": p.x}))

    def release(self, target: str) -> None:
        """Free a held part."""
        p = self._resolve(target, states=("held",))
        self._unpin(p)
        p.state = "on"
        self.events.append(PlantEvent(self.now_ns, "part released", self._locate(p.x), p.id, {"x": p.x}))

    def knock_off(self, target: str) -> None:
        """Push a part sideways off the belt: ``part knocked off`` now, ``part fell off`` when it has dropped."""
        p = self._resolve(target, states=("on", "held"))
        self._unpin(p)
        p.push_off()
        p.at_stop = False
        self.events.append(PlantEvent(self.now_ns, "part knocked off", self._locate(p.x), p.id, {"x": p.x}))
        self._exit_beams(p.id)

    # --- callbacks (pymunk calls them inside space.step; they only touch Python state) -----------------------------
    def _touch_begin(self, arbiter: pymunk.Arbiter, space: pymunk.Space, data: Any) -> None:
        ps, ss = arbiter.shapes
        ss.owner.enter(self, ps.part)

    def _touch_separate(self, arbiter: pymunk.Arbiter, space: pymunk.Space, data: Any) -> None:
        ps, ss = arbiter.shapes
        owner = getattr(ss, "owner", None)  # None while Python tears the space down (interpreter exit)
        part = getattr(ps, "part", None)
        if owner is not None and part is not None:
            owner.leave(self, part)

    def _fall_begin(self, arbiter: pymunk.Arbiter, space: pymunk.Space, data: Any) -> None:
        part = arbiter.shapes[0].part
        if part.state != "gone" and part not in self._falling:
            self._falling.append(part)
            self._post = True

    # --- helpers -------------------------------------------------------------------------------------------------
    def _drop(self, p: Part, kind: str, subject: str, data: dict) -> None:
        """Take ``p`` out of the plant with one event, then its ``part left`` events."""
        self.events.append(PlantEvent(self.now_ns, kind, subject, p.id, data))
        self._exit_beams(p.id)
        self._unpin(p)
        p.state = "gone"  # before the removal: its separate callbacks are then ignored
        self.space.remove(p.shape, p.body)
        del self.parts[p.id]
        self._live -= 1

    def _unpin(self, p: Part) -> None:
        if p.joints:
            self.space.remove(*p.joints)
            p.joints = ()

    def _exit_beams(self, pid: str) -> None:
        """The part ``pid`` left the plant: the components that track parts (the beams) forget it."""
        for c in self._gone_hooks:
            c.part_gone(self, pid)

    def _get_station(self, name: str) -> Station:
        try:
            return self.stations[name]
        except KeyError:
            raise KeyError(f"{self.name} has no station {name!r} (stations: {list(self.stations)})") from None

    def _support(self, x: float) -> Belt:
        """The belt under x, or the nearest one."""
        return min(self.belts, key=lambda b: 0.0 if b.contains(x) else min(abs(x - b.x0), abs(x - b.x1)))

    def _locate(self, x: float) -> str:
        return self._support(x).name

    def _resolve(self, target: str, states: tuple[str, ...]) -> Part:
        """A part by id, or the part at a station (the front-most one for a belt station)."""
        p = self.parts.get(target)
        if p is None:
            st = self._get_station(target)
            cands = [q for q in self.parts.values() if q.state in ("on", "held")]
            belt = self.belt_stations.get(target)
            if belt is not None:
                cands = [q for q in cands if belt.contains(q.x)]
                p = max(cands, key=lambda q: q.x * (1 if belt.direction >= 0 else -1), default=None)
            else:
                cands = [q for q in cands if abs(q.x - st.x) <= 0.5 * q.spec.length + 5.0]
                p = min(cands, key=lambda q: abs(q.x - st.x), default=None)
            if p is None:
                raise KeyError(f"{self.name}: no part at {target!r}")
        if p.state not in states:
            raise ValueError(f"{self.name}: part {p.id} is {p.state!r}, expected one of {states}")
        return p

    # --- observation -------------------------------------------------------------------------------------------
    def part_poses(self) -> dict[str, tuple[float, float, float]]:
        """{part id: (x, y, angle rad)} of every part (reads pymunk: call it at trace rate, not per step)."""
        return {pid: p.pose() for pid, p in self.parts.items()}

    def belt_speeds(self) -> dict[str, float]:
        """{belt name: current speed in mm/s}."""
        return {b.name: b.v for b in self.belts}

    def observables(self) -> dict[str, float]:
        """Analog values worth tracing that are not signals: belt speeds and the number of parts."""
        out = {f"{b.name}.v": b.v for b in self.belts}
        out["parts"] = float(len(self.parts))
        return out

    # --- drawing -----------------------------------------------------------------------------------------------------
    def _line_extent(self) -> tuple[float, float]:
        return (min(b.x0 for b in self.belts), max(b.x1 for b in self.belts))

    def bounds(self) -> tuple[float, float, float, float]:
        x0, x1 = self._line_extent()
        top = max(b.top for b in self.belts)
        xmax = x1 + 40.0
        if self.panel is not None:
            xmax = max(xmax, self.panel.extent()[2] + 10.0)
        return (x0 - 40.0, -10.0, xmax, top + 70.0)

    def static_drawables(self) -> list[Drawable]:
        x0, x1 = self._line_extent()
        out = [draw.polygon("frame/base", draw.rect(x0 - 10.0, -4.0, x1 + 10.0, 0.0), draw.FRAME)]
        return out + [d for c in self._under + self._over for d in c.static_drawables()]

    def dynamic_drawables(self) -> list[Drawable]:
        """The components under the parts (a running belt's arrow), the parts, then the rest over them (an
        interrupted beam shows red on the part)."""
        out = [d for c in self._under for d in c.dynamic_drawables()]
        for p in self.parts.values():
            color = p.props.get("color", draw.PART)
            if p.state == "held":
                color = draw.PART_HELD
            elif p.state == "off":
                color = draw.PART_OFF
            out.append(p.drawable(tuple(color)))
        return out + [d for c in self._over for d in c.dynamic_drawables()]
