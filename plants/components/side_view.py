"""The machinery every side-view belt rig shares: a pymunk space, belts, beams, end stops, parts and operator actions.

A rig (``plants.conveyors``) builds its components in ``__init__`` and hands them to :class:`SideViewPlant`, which
implements the :class:`plcsim.plant.Plant` protocol for them:

* **Space.** Side view, y up, mm/kg/s, gravity 9810 mm/s², default ``collision_slop`` (0.1 mm) and 10 iterations,
  single-threaded (a threaded space is not deterministic). ``reset`` builds a fresh space in a fixed order, so the same
  actions give bit-identical positions in any process.
* **Event-driven sensors.** Beams are sensor shapes; pymunk's ``begin``/``separate`` callbacks update the live
  ``sensors`` dict and append ``part entered`` / ``part left`` events. Nothing is queried per step.
* **Actuators on change only.** A motor command sets a belt's target speed; the belt joins a short list of belts in
  transition and writes its ``surface_velocity`` each step only until it has settled (≈ 0.6 s after a change).
* **Fell off.** A sensor zone below the belts (its top 25 mm under the lowest belt surface) catches every part that
  drops off an end or is knocked off; the part is removed after the step with a ``part fell off`` event.
* **No parts, no physics.** With no part in the space, ``step`` only advances the clock and the belt drives (the
  hours-meter exercises run for simulated hours with an empty belt).

Per step the cost is one ``space.step`` plus a few attribute reads; see ``plants/conveyors.py`` for measured figures.
Events are stamped with the time at the **end** of the step in which they happened (``now_ns`` after the step).
A placement takes effect at once, but beams see a newly placed part from the next physics step on (the same 1-step
latency as any other physical change).
"""

from __future__ import annotations

import math
from collections.abc import Iterable, Mapping
from typing import Any

import numpy as np
import pymunk

from plants.components import draw
from plants.components.belt import Belt
from plants.components.collide import (
    CT_BEAM,
    CT_FALL,
    CT_PART,
    CT_PLATE,
    CT_STOP,
    FALL_CAT,
    PLATE_CAT,
    STOP_CAT,
)
from plants.components.component import Assembly, Component
from plants.components.light_barrier import LightBarrier
from plants.components.panel import OperatorPanel
from plants.components.workpiece import STANDARD, Part, WorkpieceSpec
from plcsim.plant import (
    MOTOR_JAM,
    OBSERVABLES,
    OPERATOR,
    PART_FAULTS,
    PARTS,
    QUIESCENCE,
    SENSOR_SHIFT,
    Drawable,
    PlantEvent,
    SignalSpec,
    Station,
)
from plcsim.scenario import RigVerb

GRAVITY = 9810.0  # mm/s²


def _raw_stepper(space: pymunk.Space):
    """(function, handle) that steps ``space`` in C; falls back to ``Space.step`` if pymunk's internals differ."""
    try:
        from pymunk._chipmunk_cffi import lib

        return lib.cpSpaceStep, space._space
    except (ImportError, AttributeError):  # pragma: no cover - another pymunk release
        return (lambda _handle, dt: space.step(dt)), None


class StationOccupiedError(ValueError):
    """``place`` found another part where the new one would go (the operator cannot put a part there)."""


class EndStop:
    """A fixed stop across the belt end: parts pile up against it; a contact gives one ``end stop hit`` event."""

    def __init__(
        self,
        name: str,
        x: float,
        top: float,
        *,
        side: str = "downstream",
        height: float = 30.0,
        thickness: float = 5.0,
        friction: float = 0.3,
    ) -> None:
        if side not in ("downstream", "upstream"):
            raise ValueError(f"end stop side must be 'downstream' or 'upstream', not {side!r}")
        self.name = name
        self.x = float(x)  # the face the parts touch
        self.top = float(top)
        self.side = side
        self.height = float(height)
        self.thickness = float(thickness)
        self.friction = float(friction)

    def box(self) -> tuple[float, float, float, float]:
        x0, x1 = (self.x, self.x + self.thickness) if self.side == "downstream" else (self.x - self.thickness, self.x)
        return (x0, self.top - 10.0, x1, self.top + self.height)

    def attach(self, space: pymunk.Space) -> pymunk.Poly:
        x0, y0, x1, y1 = self.box()
        shape = pymunk.Poly(space.static_body, [(x0, y0), (x1, y0), (x1, y1), (x0, y1)])
        shape.friction = self.friction
        shape.collision_type = CT_STOP
        shape.filter = pymunk.ShapeFilter(categories=STOP_CAT)
        shape.stop = self
        space.add(shape)
        return shape


class DeadPlate:
    """A fixed plate that bridges the gap between two belts, 0.5 mm below the belt surface.

    A 30 mm part crosses a 5 mm gap without ever touching it (it is carried by the belts on both sides); the plate is
    there to stop the part tipping into the gap and to be drawn. Level with the belts it would catch the leading
    corner (checked: a level plate stops a part dead at the gap).
    """

    def __init__(
        self, name: str, x0: float, x1: float, top: float, *, drop: float = 0.5, friction: float = 0.1
    ) -> None:
        self.name = name
        self.x0 = float(x0)
        self.x1 = float(x1)
        self.top = float(top) - drop
        self.friction = float(friction)

    def attach(self, space: pymunk.Space) -> pymunk.Segment:
        r = 1.0
        seg = pymunk.Segment(space.static_body, (self.x0 - r, self.top - r), (self.x1 + r, self.top - r), r)
        seg.friction = self.friction
        seg.collision_type = CT_PLATE
        seg.filter = pymunk.ShapeFilter(categories=PLATE_CAT)
        space.add(seg)
        return seg


class SideViewPlant:
    """Base class of the side-view belt rigs (see the module docstring).

    Args:
        name: plant name (``CONV1``).
        belts: the belts, upstream first.
        motors: actuator name -> (belt, direction +1/-1). Two actuators driving one belt in opposite directions at
            the same time stop it and log ``interlock violated``.
        barriers: the light barriers (sensor names).
        stations: named places for ``place``/``remove``; ``belt_stations`` maps the ones that mean "a belt" (the
            station is the belt's upstream end and ``offset_mm`` is the position along it) to their belt.
        end_stops, dead_plates: fixed parts of the frame.
        panel: optional operator panel (buttons, switches, lamps) shown beside the machine.
        components: further pieces of the rig on the component protocol (``plants.components.component``: an
            axis, a piston); their signals, events and drawings join the rig's, and they are stepped while busy.
        signal_docs: doc strings of the signals (by name).
        seed: initial seed (the belt rigs have no randomness of their own; ``rng`` is offered to subclasses).
        max_step_ns: a ``step`` longer than this is split into equal sub-steps (physics stays stable at coarse scans).
    """

    view = "side"
    EVENTS = OperatorPanel.EVENTS | {
        "part placed",
        "part removed",
        "part entered",
        "part left",
        "part fell off",
        "end stop hit",
        "part jammed",
        "part released",
        "part knocked off",
        "motor jammed",
        "interlock violated",
    }
    """Every kind of event the rig can emit (the panel's only with a panel)."""
    CAPABILITIES = frozenset({PARTS, PART_FAULTS, QUIESCENCE, SENSOR_SHIFT, MOTOR_JAM, OBSERVABLES, OPERATOR})
    """What the rig offers besides the core (operator controls only with a panel)."""
    VERBS: dict[str, RigVerb] = {}
    """The rig's own scenario verbs (a subclass adds to a copy of it)."""

    def __init__(
        self,
        name: str,
        *,
        belts: Iterable[Belt],
        motors: Mapping[str, tuple[Belt, int]],
        barriers: Iterable[LightBarrier],
        stations: Iterable[Station],
        belt_stations: Mapping[str, Belt] | None = None,
        end_stops: Iterable[EndStop] = (),
        dead_plates: Iterable[DeadPlate] = (),
        panel: OperatorPanel | None = None,
        components: Iterable[Component] = (),
        signal_docs: Mapping[str, str] | None = None,
        workpiece: WorkpieceSpec = STANDARD,
        seed: int = 0,
        max_step_ns: int = 5_000_000,
    ) -> None:
        self.name = name
        self.belts = list(belts)
        self.motors = dict(motors)
        self.barriers = list(barriers)
        self.barrier = {b.name: b for b in self.barriers}
        self.end_stops = list(end_stops)
        self.dead_plates = list(dead_plates)
        self.panel = panel
        self.assembly = Assembly(components)
        if self.assembly.components:
            self.EVENTS = self.EVENTS | self.assembly.events
        if panel is None:
            self.EVENTS = self.EVENTS - OperatorPanel.EVENTS
            self.CAPABILITIES = self.CAPABILITIES - {OPERATOR}
        self.workpiece = workpiece
        self.max_step_ns = int(max_step_ns)
        self.stations: dict[str, Station] = {s.name: s for s in stations}
        self.belt_stations = dict(belt_stations or {})
        self._belt_by_name = {b.name: b for b in self.belts}
        docs = dict(signal_docs or {})
        specs = [SignalSpec(b.name, "sensor", doc=docs.get(b.name, b.doc)) for b in self.barriers]
        specs += [SignalSpec(m, "actuator", doc=docs.get(m, "")) for m in self.motors]
        if panel is not None:
            specs += panel.specs()
        specs += self.assembly.specs()
        names = [s.name for s in specs]
        dup = sorted({n for n in names if names.count(n) > 1})
        if dup:
            raise ValueError(f"{name}: duplicate signal names {dup}")
        self.signals: dict[str, SignalSpec] = {s.name: s for s in specs}
        self.sensors: dict[str, Any] = {}
        self.events: list[PlantEvent] = []
        self.seed = seed
        self.reset(seed=seed)

    def event_subjects(self) -> set[str]:
        """Every ``subject`` its events can name: beams, stations, belts, end stops, motors, panel controls."""
        names = set(self.barrier) | set(self.stations) | set(self._belt_by_name) | set(self.motors)
        names |= {s.name for s in self.end_stops} | set(self.panel.controls if self.panel is not None else ())
        return names | self.assembly.subjects()

    # --- what a component sees of the rig (plants.components.component.Host) ---------------------------------
    def emit(self, kind: str, subject: str, part: str | None = None, **data: Any) -> None:
        """Record a plant event at the current time."""
        self.events.append(PlantEvent(self.now_ns, kind, subject, part, data))

    def wake(self, component: Component) -> None:
        """Step ``component`` from the next step on."""
        self.assembly.wake(component)

    # --- protocol: lifecycle ---------------------------------------------------------------------------------
    def reset(self, *, seed: int | None = None) -> None:
        """Back to the initial state: a new space, no parts, motors off, faults cleared, time 0."""
        if seed is not None:
            self.seed = seed
        self.rng = np.random.default_rng(self.seed)
        self.now_ns = 0
        self.events.clear()  # the same list and dict objects: the wiring may hold references to them
        self.sensors.clear()
        self.sensors.update(dict.fromkeys((b.name for b in self.barriers), False))
        if self.panel is not None:
            self.panel.reset()
            self.sensors.update(self.panel.initial_sensors())
        self.motor_state: dict[str, bool] = dict.fromkeys(self.motors, False)
        old = getattr(self, "space", None)
        if old is not None:  # a freed space calls `separate` for its contacts: keep them away from the new state
            for pair in ((CT_PART, CT_BEAM), (CT_PART, CT_STOP), (CT_PART, CT_FALL)):
                old.on_collision(*pair, begin=pymunk.empty_callback, separate=pymunk.empty_callback)
        space = pymunk.Space()
        space.gravity = (0.0, -GRAVITY)
        space.iterations = 10
        self.space = space
        for b in self.belts:
            b.reset()
            b.attach(space)
        for p in self.dead_plates:
            p.attach(space)
        for s in self.end_stops:
            s.attach(space)
        for lb in self.barriers:
            lb.reset()
            lb.attach(space)
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
        space.on_collision(CT_PART, CT_BEAM, begin=self._beam_begin, separate=self._beam_separate)
        space.on_collision(CT_PART, CT_STOP, begin=self._stop_begin, separate=self._stop_separate)
        space.on_collision(CT_PART, CT_FALL, begin=self._fall_begin)
        # pymunk's Space.step wraps cpSpaceStep in bookkeeping for adding/removing objects inside callbacks (which
        # this plant never does: it defers removals to after the step) and costs 0.8 µs more than the physics of a
        # one-part belt. The plant calls the C step directly except in the step right after a body was added.
        self._cp_step, self._cp_space = _raw_stepper(space)
        self._fresh = False
        self.parts: dict[str, Part] = {}
        self._next_id = 1
        self._live = 0  # parts in the space
        self._drawable_cache: dict[tuple, Drawable] = {}
        self._transient: list[Belt] = []
        self._falling: list[Part] = []
        self._rebuild: list[LightBarrier] = []
        self._post = False
        self.assembly.reset(self)

    def quiescent(self) -> bool:
        """True when a step would only advance the clock: no part in the plant and every drive settled.

        A quiescent plant may be stepped by any ``dt_ns`` at once; the simulator uses this to skip
        the steps of an idle machine (an hours meter counting a belt that runs empty).
        """
        return not self._live and not self._transient and not self.assembly.busy

    def step(self, dt_ns: int) -> None:
        """Advance by ``dt_ns``: belt drives in transition, then one physics step (skipped with no parts)."""
        busy = self.assembly.busy
        if not self._live and not self._transient and not busy and dt_ns > 0:
            self.now_ns += dt_ns
            return
        if dt_ns > self.max_step_ns or dt_ns <= 0:
            self._step_split(dt_ns)
            return
        self.now_ns += dt_ns
        dt = dt_ns / 1e9
        if self._transient:
            self._advance_belts(dt)
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

    def _step_split(self, dt_ns: int) -> None:
        dt_ns = int(dt_ns)
        if dt_ns <= 0:
            raise ValueError(f"step: dt_ns must be > 0, not {dt_ns}")
        n = -(-dt_ns // self.max_step_ns)
        base, rem = divmod(dt_ns, n)
        for k in range(n):
            self.step(base + (1 if k < rem else 0))

    def _advance_belts(self, dt: float) -> None:
        self._transient = [b for b in self._transient if b.advance(dt)]

    def _after_step(self) -> None:
        self._post = False
        if self._falling:
            falling, self._falling = self._falling, []
            for part in falling:
                if part.state != "gone":
                    self._drop(part, "part fell off", self._locate(part.x), {"x": part.x})
        if self._rebuild:
            rebuild, self._rebuild = self._rebuild, []
            for lb in rebuild:
                self._finish_rebuild(lb)

    # --- protocol: actuators and operator ----------------------------------------------------------------------
    def actuate(self, name: str, value: Any) -> None:
        """A PLC output changed. Motors: True = run; lamps: True = lit."""
        m = self.motors.get(name)
        if m is not None:
            value = bool(value)
            if self.motor_state[name] == value:
                return
            self.motor_state[name] = value
            belt = m[0]
            fwd = back = False
            for act, (b, sign) in self.motors.items():
                if b is belt and self.motor_state[act]:
                    if sign > 0:
                        fwd = True
                    else:
                        back = True
            if fwd and back:
                self.events.append(
                    PlantEvent(
                        self.now_ns, "interlock violated", belt.name, None, {"reason": "both directions commanded"}
                    )
                )
                direction = 0
            else:
                direction = 1 if fwd else (-1 if back else 0)
            if belt.command(direction) and belt not in self._transient:
                self._transient.append(belt)
            return
        if self.panel is not None and name in self.panel.lamps:
            self.panel.set_lamp(name, value)
            return
        if self.assembly.owns(name):
            self.assembly.actuate(self, name, value)
            return
        raise KeyError(f"{self.name} has no actuator {name!r} (actuators: {self._actuator_names()})")

    def _actuator_names(self) -> list[str]:
        return [n for n, s in self.signals.items() if s.direction == "actuator"]

    def operate(self, name: str, value: Any) -> None:
        """The operator sets a button or switch on the rig's panel."""
        if self.panel is None:
            raise KeyError(f"{self.name} has no operator controls (a panel was not configured)")
        self.panel.operate(name, value, self.sensors, self.events, self.now_ns)

    # --- faults --------------------------------------------------------------------------------------------------
    def shift_sensor(self, name: str, dx_mm: float) -> None:
        """Fault: the light barrier ``name`` is mounted ``dx_mm`` off its nominal place (absolute, not cumulative).

        The beam is moved at once; which parts it sees is re-detected by the next physics step, and only the
        difference is reported (no spurious edge for a part that stays in the beam). A cam or switch of a
        component (an axis) is shifted by its component.
        """
        if name not in self.barrier and self.assembly.owns(name):
            self.assembly.shift(self, name, dx_mm)
            return
        lb = self._get_barrier(name)
        dx = float(dx_mm)
        if dx == lb.dx:
            return
        if lb.rebuilding is None:
            lb.rebuilding = dict(lb.parts)
        lb.parts = {}
        lb.dx = dx
        self.space.remove(lb.shape)  # separate callbacks: nothing is a member any more, they are ignored
        lb.attach(self.space)
        if self._live:
            if lb not in self._rebuild:
                self._rebuild.append(lb)
            self._post = True
        else:
            self._finish_rebuild(lb)

    def jam_motor(self, name: str, jammed: bool = True) -> None:
        """Fault: the motor (actuator name, or belt name) is blocked: commanded or not, its belt does not move.
        The drive of a component (an axis, by its name or an actuator of it) is jammed by its component."""
        if name not in self.motors and name not in self._belt_by_name and self.assembly.has(name):
            self.assembly.jam(self, name, jammed)
            return
        belt = self._get_belt(name)
        was = belt.jammed
        if belt.jam(jammed) and belt not in self._transient:
            self._transient.append(belt)
        if belt.jammed and not was:
            self.events.append(
                PlantEvent(
                    self.now_ns, "motor jammed", name, None, {"belt": belt.name, "commanded": belt.direction != 0}
                )
            )

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
    def _beam_begin(self, arbiter: pymunk.Arbiter, space: pymunk.Space, data: Any) -> None:
        ps, bs = arbiter.shapes
        part = ps.part
        if part.state == "off" or part.state == "gone":
            return
        lb = bs.barrier
        lb.begins += 1
        if part.id in lb.parts:
            return
        lb.parts[part.id] = None
        if lb.rebuilding is None:
            self.sensors[lb.name] = True
            self.events.append(PlantEvent(self.now_ns, "part entered", lb.name, part.id))

    def _beam_separate(self, arbiter: pymunk.Arbiter, space: pymunk.Space, data: Any) -> None:
        ps, bs = arbiter.shapes
        lb = getattr(bs, "barrier", None)  # None while Python tears the space down (interpreter exit)
        part = getattr(ps, "part", None)
        if lb is None or part is None or part.id not in lb.parts:
            return
        pid = part.id
        lb.separates += 1
        del lb.parts[pid]
        if lb.rebuilding is None:
            self.sensors[lb.name] = bool(lb.parts)
            self.events.append(PlantEvent(self.now_ns, "part left", lb.name, pid))

    def _stop_begin(self, arbiter: pymunk.Arbiter, space: pymunk.Space, data: Any) -> None:
        ps, ss = arbiter.shapes
        part = ps.part
        if part.at_stop or part.state in ("off", "gone"):
            return
        part.at_stop = True
        self.events.append(
            PlantEvent(self.now_ns, "end stop hit", ss.stop.name, part.id, {"speed": abs(part.body.velocity.x)})
        )

    def _stop_separate(self, arbiter: pymunk.Arbiter, space: pymunk.Space, data: Any) -> None:
        part = getattr(arbiter.shapes[0], "part", None)
        if part is not None:
            part.at_stop = False

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
        for lb in self.barriers:
            if lb.rebuilding is not None:
                lb.parts.pop(pid, None)
                if pid in lb.rebuilding:
                    del lb.rebuilding[pid]
                    self.sensors[lb.name] = bool(lb.rebuilding)
                    self.events.append(PlantEvent(self.now_ns, "part left", lb.name, pid))
            elif pid in lb.parts:
                del lb.parts[pid]
                lb.separates += 1
                self.sensors[lb.name] = bool(lb.parts)
                self.events.append(PlantEvent(self.now_ns, "part left", lb.name, pid))

    def _finish_rebuild(self, lb: LightBarrier) -> None:
        old, lb.rebuilding = lb.rebuilding or {}, None
        for pid in old:
            if pid not in lb.parts:
                self.events.append(PlantEvent(self.now_ns, "part left", lb.name, pid, {"cause": "sensor shifted"}))
        for pid in lb.parts:
            if pid not in old:
                self.events.append(PlantEvent(self.now_ns, "part entered", lb.name, pid, {"cause": "sensor shifted"}))
        self.sensors[lb.name] = bool(lb.parts)

    def _get_station(self, name: str) -> Station:
        try:
            return self.stations[name]
        except KeyError:
            raise KeyError(f"{self.name} has no station {name!r} (stations: {list(self.stations)})") from None

    def _get_barrier(self, name: str) -> LightBarrier:
        try:
            return self.barrier[name]
        except KeyError:
            raise KeyError(f"{self.name} has no light barrier {name!r} (have {list(self.barrier)})") from None

    def _get_belt(self, name: str) -> Belt:
        if name in self.motors:
            return self.motors[name][0]
        if name in self._belt_by_name:
            return self._belt_by_name[name]
        raise KeyError(f"{self.name} has no motor or belt {name!r} (motors: {list(self.motors)})")

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
        out: list[Drawable] = []
        x0, x1 = self._line_extent()
        out.append(draw.polygon("frame/base", draw.rect(x0 - 10.0, -4.0, x1 + 10.0, 0.0), draw.FRAME))
        for b in self.belts:
            for k, xl in enumerate((b.x0 + 15.0, b.x1 - 23.0)):
                leg = draw.rect(xl, 0.0, xl + 8.0, b.top - 10.0)
                out.append(draw.polygon(f"frame/legs/{b.name}/{k}", leg, draw.FRAME))
            out.append(draw.polygon(f"belt/{b.name}", draw.stadium(b.x0, b.x1, b.top - 10.0, b.top), draw.BELT, b.name))
            out.append(draw.label(f"belt/{b.name}/label", 0.5 * (b.x0 + b.x1), b.top - 20.0, b.name))
        for p in self.dead_plates:
            out.append(draw.polygon(f"frame/{p.name}", draw.rect(p.x0, p.top - 3.0, p.x1, p.top), draw.DEAD_PLATE))
        for s in self.end_stops:
            bx0, by0, bx1, by1 = s.box()
            out.append(draw.polygon(f"frame/{s.name}", draw.rect(bx0, by0, bx1, by1), draw.END_STOP, s.name))
        for lb in self.barriers:
            out.append(
                draw.line(f"sensors/{lb.name}", [(lb.x, lb.y - 10.0), (lb.x, lb.y + 30.0)], draw.SENSOR, lb.name)
            )
            out.append(draw.label(f"sensors/{lb.name}/label", lb.x, lb.y + 36.0, lb.name))
        if self.panel is not None:
            out += self.panel.static_drawables("panel")
        return out + self.assembly.static_drawables()

    def dynamic_drawables(self) -> list[Drawable]:
        cache = self._drawable_cache
        out: list[Drawable] = []
        for b in self.belts:
            if b.v != 0.0:
                key = ("arrow", b.name, b.v > 0)
                arrow = cache.get(key)
                if arrow is None:
                    xm = 0.5 * (b.x0 + b.x1)
                    d = 15.0 if b.v > 0 else -15.0
                    arrow = cache[key] = draw.arrow(
                        f"belt/{b.name}/direction", xm - d, xm + d, b.top - 5.0, draw.BELT_RUNNING
                    )
                out.append(arrow)
        for pid, p in self.parts.items():
            color = p.props.get("color", draw.PART)
            if p.state == "held":
                color = draw.PART_HELD
            elif p.state == "off":
                color = draw.PART_OFF
            out.append(Drawable(f"parts/{pid}", "polygon", p.outline(), tuple(color), text=pid))
        for lb in self.barriers:  # over the parts: an interrupted beam shows red on the part
            on = self.sensors[lb.name]
            key = ("beam", lb.name, on, lb.x_actual)
            beam = cache.get(key)
            if beam is None:  # drawables are frozen, so one per state is shared by every frame
                beam = cache[key] = draw.circle(
                    f"beams/{lb.name}", lb.x_actual, lb.y, 2.5, draw.BEAM_CUT if on else draw.BEAM_FREE, lb.name
                )
            out.append(beam)
        if self.panel is not None:
            out += self.panel.dynamic_drawables(self.sensors, "panel")
        return out + self.assembly.dynamic_drawables()
