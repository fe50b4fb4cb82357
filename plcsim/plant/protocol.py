"""The Plant protocol: what the scheduler, the wiring, scenarios and traces need from a machine model.

A plant knows nothing of PLCs. It has named signals: **sensors** it reports (a light barrier is
``True`` while its beam is interrupted, a button while pressed, a limit switch while actuated) and
**actuators** it obeys (a belt motor, a lamp, a piston valve). The wiring maps them to PLC addresses
(NO/NC, scaling, faults). Units are mm, g and s; time is integer nanoseconds.

The **core** (:class:`Plant`) is what every machine has, a press or a crane as much as a belt line:
signals, reset, actuate, step, events and drawing. Everything else is an optional **capability**
the plant *declares* in ``CAPABILITIES`` (a frozenset of the names below), never found by probing
for methods; :func:`capable` reads the declaration and :func:`check_plant` checks it is kept:

* :data:`PARTS` — ``stations``, ``place(station, ...)``, ``remove(target)`` (:class:`HandlesParts`);
* :data:`PART_FAULTS` — ``hold``, ``release``, ``knock_off`` on a part (:class:`PartFaults`; a belt line);
* :data:`OPERATOR` — ``operate(name, value)`` for its buttons and switches (:class:`Operated`);
* :data:`QUIESCENCE` — ``quiescent()``: True when a step would only advance the clock, so any number
  of steps may be taken at once (the simulator then skips an idle machine's steps);
* :data:`SENSOR_SHIFT` — ``shift_sensor(name, dx_mm)``; :data:`MOTOR_JAM` — ``jam_motor(name, jammed)``;
* :data:`OBSERVABLES` — ``observables() -> dict[str, float]``: analog values worth tracing. Those the
  trace records in every row are named in ``TRACED_OBSERVABLES`` (optional; a press's ram height), read
  together by ``sample_observables()`` (a tuple in that order, cheap: it runs once per scan); the trace
  calls their columns ``plant:<name>`` (kind ``analog``; :func:`traced_observables`).

A plant declares its **event vocabulary**: ``EVENTS`` (every kind it can emit) and
``event_subjects()`` (every name its events can be about, a part's id aside). An exercise whose check
or scenario waits for an event its rig never emits is refused when it is loaded.

A rig may bring its own **scenario verbs** (``set_colour``, ``jam_piston``): ``VERBS`` maps each name
to a :class:`plcsim.scenario.verbs.RigVerb`, which builds the action and names the plant method that
carries it out, so that adding one needs no edit in ``plcsim``.

Performance contract (the co-simulation budget depends on it): :attr:`Plant.sensors` is a live
dict that :meth:`Plant.step` keeps up to date, so reading it costs a dict lookup; :meth:`Plant.actuate`
is called only when an output changes.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, Literal, Protocol, runtime_checkable

import numpy as np

if TYPE_CHECKING:
    from plcsim.scenario.verbs import RigVerb


@dataclass(frozen=True)
class SignalSpec:
    """One plant signal.

    Attributes:
        name: the plant's name for it (``S1``, ``D1``, ``TLACIDLO``).
        direction: ``sensor`` (plant -> PLC input) or ``actuator`` (PLC output -> plant).
        kind: ``bool`` or ``analog``.
        doc: what it means physically ("light barrier at 40 mm: True while interrupted").
        unit, lo, hi: physical unit and range of an analog signal.
        operator: True for a sensor the operator drives (a button or switch on a panel).
    """

    name: str
    direction: Literal["sensor", "actuator"]
    kind: Literal["bool", "analog"] = "bool"
    doc: str = ""
    unit: str = ""
    lo: float = 0.0
    hi: float = 1.0
    operator: bool = False


@dataclass(frozen=True)
class Station:
    """A named place where an operator can put or take a part (``S1``, ``loading``, ``D3_OS``)."""

    name: str
    x: float
    y: float = 0.0
    doc: str = ""


@dataclass(frozen=True)
class PlantEvent:
    """Something that happened in the plant, stamped with simulated time.

    ``kind`` is one of a small vocabulary checks can rely on: ``part placed``, ``part removed``,
    ``part entered``, ``part left`` (a sensor zone, ``subject`` = the sensor), ``part fell off``,
    ``end stop hit``, ``part jammed``, ``part released``, ``part knocked off``, ``motor jammed``,
    ``interlock violated``, ``button pressed``, ``button released``; the component rigs add ``axis stalled``,
    ``piston extended``, ``piston retracted``, ``piston jammed``, ``compressor failed``, ``part in bin`` and
    ``alignment measured`` (``data`` carries what a check grades: ``event_data(kind, key)``). A plant declares
    the kinds it can emit as a class attribute ``EVENTS`` (a set of strings) and the subjects they can name (a part's id
    aside) with a method ``event_subjects()``; an exercise then refuses, when it is loaded, a check or
    trigger waiting for an event the plant never emits, or for one about a name it does not have.
    """

    t_ns: int
    kind: str
    subject: str
    part: str | None = None
    data: Mapping[str, Any] = field(default_factory=dict)


@dataclass(frozen=True)
class Drawable:
    """One shape to draw, in plant coordinates (mm, y up).

    Attributes:
        path: entity path below the plant, e.g. ``belt/D1``, ``parts/p3``, ``beams/S1``.
        kind: ``polygon`` (closed), ``line`` (open polyline), ``circle`` or ``label``.
        points: (N, 2) array of vertices; a circle or label has one point.
        color: RGB 0..255.
        radius: for circles.
        text: label text, or a short caption for the shape.
    """

    path: str
    kind: Literal["polygon", "line", "circle", "label"]
    points: np.ndarray
    color: tuple[int, int, int] = (128, 128, 128)
    radius: float = 0.0
    text: str = ""


PARTS = "parts"
"""Capability: ``stations``, ``place`` and ``remove`` (an operator puts parts in and takes them out)."""
PART_FAULTS = "part faults"
"""Capability: ``hold``, ``release`` and ``knock_off`` (a part jammed on a belt, or pushed off it)."""
OPERATOR = "operator"
"""Capability: ``operate`` (buttons and switches: sensors with ``operator=True``)."""
QUIESCENCE = "quiescence"
"""Capability: ``quiescent()``, True when a step would only advance the clock."""
SENSOR_SHIFT = "sensor shift"
"""Capability: ``shift_sensor(name, dx_mm)``, a sensor mounted off its place (a fault)."""
MOTOR_JAM = "motor jam"
"""Capability: ``jam_motor(name, jammed)``, a blocked drive (a fault)."""
OBSERVABLES = "observables"
"""Capability: ``observables()``, analog values worth tracing that are not signals."""

CAPABILITY_MEMBERS: dict[str, tuple[str, ...]] = {
    PARTS: ("stations", "place", "remove"),
    PART_FAULTS: ("hold", "release", "knock_off"),
    OPERATOR: ("operate",),
    QUIESCENCE: ("quiescent",),
    SENSOR_SHIFT: ("shift_sensor",),
    MOTOR_JAM: ("jam_motor",),
    OBSERVABLES: ("observables",),
}
"""The members each capability stands for (what a plant declaring it must have)."""


@runtime_checkable
class Plant(Protocol):
    """The core every machine model has; see the module docstring for the optional capabilities."""

    name: str
    view: Literal["side", "top", "panel"]
    signals: Mapping[str, SignalSpec]
    sensors: dict[str, Any]
    now_ns: int
    events: list[PlantEvent]
    EVENTS: frozenset[str] | set[str]
    CAPABILITIES: frozenset[str]
    VERBS: Mapping[str, RigVerb]

    def reset(self, *, seed: int | None = None) -> None:
        """Back to the initial state (no parts, actuators off, time 0)."""

    def actuate(self, name: str, value: Any) -> None:
        """A PLC output changed: apply the new command (from the next step on)."""

    def step(self, dt_ns: int) -> None:
        """Advance the physics by ``dt_ns`` and update :attr:`sensors` and :attr:`events`."""

    def event_subjects(self) -> set[str]:
        """Every name its events can be about (a sensor, a station, a piston), a part's id aside."""

    def static_drawables(self) -> list[Drawable]:
        """Shapes that never move (frame, belts, sensor positions), drawn once."""

    def dynamic_drawables(self) -> list[Drawable]:
        """Shapes of the current state (parts, lit beams, lamps, piston rods)."""

    def bounds(self) -> tuple[float, float, float, float]:
        """The area to show: (xmin, ymin, xmax, ymax) in mm."""


class HandlesParts(Protocol):
    """Capability :data:`PARTS`: an operator puts parts at named stations and takes them away."""

    stations: Mapping[str, Station]

    def place(
        self,
        station: str,
        *,
        part: str | None = None,
        offset_mm: float = 0.0,
        angle_deg: float = 0.0,
        **properties: Any,
    ) -> str:
        """Put a new part at a station (with the given pose error); returns its id."""

    def remove(self, target: str) -> None:
        """Take away a part, by id or by the station it is at."""


class PartFaults(Protocol):
    """Capability :data:`PART_FAULTS`: a part jammed where it is, freed, or pushed off the machine."""

    def hold(self, target: str) -> None:
        """Jam a part: it is held in place (a belt slips under it) until :meth:`release`."""

    def release(self, target: str) -> None:
        """Free a held part."""

    def knock_off(self, target: str) -> None:
        """Push a part off the machine (it falls off the belt)."""


class Operated(Protocol):
    """Capability :data:`OPERATOR`: buttons and switches the operator sets."""

    def operate(self, name: str, value: Any) -> None:
        """The operator sets a button or switch (a sensor with ``operator=True``)."""


def capable(plant: Any, capability: str) -> bool:
    """Whether ``plant`` declares ``capability`` (False for no plant).

    >>> class Press:
    ...     CAPABILITIES = frozenset({QUIESCENCE})
    >>> capable(Press(), QUIESCENCE), capable(Press(), PARTS), capable(None, PARTS)
    (True, False, False)
    """
    return plant is not None and capability in plant.CAPABILITIES


def stations_of(plant: Any) -> dict[str, Station]:
    """The plant's stations (none if it does not handle parts)."""
    return dict(plant.stations) if capable(plant, PARTS) else {}


def rig_verbs(plant: Any) -> Mapping[str, RigVerb]:
    """The scenario verbs the plant brings (none for no plant)."""
    return {} if plant is None else plant.VERBS


def traced_observables(plant: Any) -> tuple[list[str], Any] | None:
    """The trace columns of the plant's ``TRACED_OBSERVABLES`` and the function sampling them (None: none).

    >>> class Press:
    ...     CAPABILITIES = frozenset({OBSERVABLES})
    ...     TRACED_OBSERVABLES = ("M2.z",)
    ...     def sample_observables(self): return (105.5,)
    >>> names, sample = traced_observables(Press())
    >>> names, sample()
    (['plant:M2.z'], (105.5,))
    """
    names = getattr(plant, "TRACED_OBSERVABLES", ()) if capable(plant, OBSERVABLES) else ()
    if not names:
        return None
    return [f"plant:{n}" for n in names], plant.sample_observables


def check_plant(plant: Plant, *, seed: int = 1234, steps: int = 300, dt_ns: int = 1_000_000) -> dict[str, Any]:
    """Check that ``plant`` keeps the protocol; raise ``AssertionError`` listing every problem found.

    Independent of the CPU. It runs the same short exercise twice after ``reset(seed=seed)`` (every operator control
    switched on, then every boolean actuator on, a part placed at the first station if there is one, ``steps`` steps
    of ``dt_ns``, operator controls off again) and checks:

    * the declared signals: names match their keys, directions and kinds are valid, every sensor is in
      ``plant.sensors`` and ``plant.sensors`` holds nothing undeclared (so every declared signal is a sensor there or
      an actuator); stations are :class:`Station` objects under their own names;
    * the declarations: ``EVENTS`` is a set of strings; every capability in ``CAPABILITIES`` is known and the plant
      has its members; every rig verb in ``VERBS`` is a :class:`~plcsim.scenario.verbs.RigVerb` under its own name whose
      method the plant has;
    * ``reset`` gives time 0, no events and the same sensors; ``operate`` sets operator sensors;
    * every ``step`` advances ``now_ns`` by exactly ``dt_ns``;
    * events are :class:`PlantEvent` with integer times in ``[0, now_ns]``, in time order, of a declared kind and
      about a declared subject (or a part);
    * drawables have ``(N, 2)`` finite float points (N ≥ 3 for polygons, ≥ 2 for lines, 1 for circles and labels),
      RGB colours and a path; ``bounds`` is a proper rectangle;
    * both runs give identical sensors, events and geometry (determinism).

    Returns a summary: ``{"signals", "events", "drawables", "digest"}`` (digest = sha256 of the second run).
    """
    import hashlib

    problems: list[str] = []

    def need(cond: bool, msg: str) -> None:
        if not cond:
            problems.append(msg)

    need(isinstance(plant, Plant), f"{type(plant).__name__} lacks members of the Plant protocol")
    _check_declarations(plant, need)
    signals = dict(plant.signals)
    for key, spec in signals.items():
        need(isinstance(spec, SignalSpec), f"signal {key!r}: not a SignalSpec")
        if not isinstance(spec, SignalSpec):
            continue
        need(spec.name == key, f"signal {key!r}: spec is named {spec.name!r}")
        need(spec.direction in ("sensor", "actuator"), f"signal {key!r}: direction {spec.direction!r}")
        need(spec.kind in ("bool", "analog"), f"signal {key!r}: kind {spec.kind!r}")
        need(not spec.operator or spec.direction == "sensor", f"signal {key!r}: an operator signal must be a sensor")
    sensor_names = [k for k, s in signals.items() if getattr(s, "direction", None) == "sensor"]
    actuators = [k for k, s in signals.items() if getattr(s, "direction", None) == "actuator"]
    operator = [k for k in sensor_names if signals[k].operator]
    need(not operator or capable(plant, OPERATOR), f"operator signals {operator} but no {OPERATOR!r} capability")
    stations = stations_of(plant)
    for key, st in stations.items():
        need(isinstance(st, Station) and st.name == key, f"station {key!r}: not a Station of that name")

    def check_drawables(where: str, items: list[Drawable]) -> None:
        minimum = {"polygon": 3, "line": 2}
        for d in items:
            need(isinstance(d, Drawable), f"{where}: {d!r} is not a Drawable")
            if not isinstance(d, Drawable):
                continue
            p = d.points
            ok = isinstance(p, np.ndarray) and p.ndim == 2 and p.shape[1] == 2 and p.shape[0] >= 1
            need(ok, f"{where} {d.path}: points must be an (N, 2) array, got {getattr(p, 'shape', type(p))}")
            if ok:
                need(bool(np.all(np.isfinite(p))), f"{where} {d.path}: points are not finite")
                if d.kind in minimum:
                    need(p.shape[0] >= minimum[d.kind], f"{where} {d.path}: a {d.kind} needs {minimum[d.kind]}+ points")
                else:
                    need(p.shape[0] == 1, f"{where} {d.path}: a {d.kind} has one point, got {p.shape[0]}")
            need(d.kind in ("polygon", "line", "circle", "label"), f"{where} {d.path}: kind {d.kind!r}")
            need(bool(d.path) and isinstance(d.path, str), f"{where}: drawable without a path")
            need(len(d.color) == 3 and all(0 <= c <= 255 for c in d.color), f"{where} {d.path}: colour {d.color}")

    def run() -> tuple:
        plant.reset(seed=seed)
        need(plant.now_ns == 0, f"reset: now_ns = {plant.now_ns}, expected 0")
        need(len(plant.events) == 0, f"reset: {len(plant.events)} events left")
        for k in sensor_names:
            need(k in plant.sensors, f"sensor {k!r} is declared but missing from plant.sensors")
        for k in plant.sensors:
            need(k in signals and signals[k].direction == "sensor", f"plant.sensors has undeclared {k!r}")
        start = dict(plant.sensors)
        for k in operator:
            plant.operate(k, True)
            need(bool(plant.sensors.get(k)) is True, f"operate({k!r}, True) did not set the sensor")
        for k in actuators:
            if signals[k].kind == "bool":
                plant.actuate(k, True)
            else:
                plant.actuate(k, 0.5 * (signals[k].lo + signals[k].hi))
        if stations:
            plant.place(next(iter(stations)))
        for _ in range(steps):
            t0 = plant.now_ns
            plant.step(dt_ns)
            if plant.now_ns != t0 + dt_ns:
                problems.append(f"step({dt_ns}) moved now_ns from {t0} to {plant.now_ns}")
                break
        for k in operator:
            plant.operate(k, False)
            need(bool(plant.sensors.get(k)) is False, f"operate({k!r}, False) did not clear the sensor")
        last = 0
        subjects = plant.event_subjects()
        for e in plant.events:
            need(isinstance(e, PlantEvent), f"event {e!r} is not a PlantEvent")
            if not isinstance(e, PlantEvent):
                continue
            need(isinstance(e.t_ns, int), f"event {e.kind!r}: t_ns {e.t_ns!r} is not an int")
            need(0 <= e.t_ns <= plant.now_ns, f"event {e.kind!r}: t_ns {e.t_ns} outside [0, {plant.now_ns}]")
            need(e.t_ns >= last, f"event {e.kind!r} at {e.t_ns} ns comes after one at {last} ns")
            need(bool(e.kind) and isinstance(e.kind, str), f"event at {e.t_ns} ns has no kind")
            need(e.kind in plant.EVENTS, f"event {e.kind!r} is not among the declared EVENTS")
            need(e.subject in subjects, f"event {e.kind!r}: undeclared subject {e.subject!r}")
            last = max(last, e.t_ns)
        static, dynamic = plant.static_drawables(), plant.dynamic_drawables()
        check_drawables("static", static)
        check_drawables("dynamic", dynamic)
        b = plant.bounds()
        need(len(b) == 4 and all(np.isfinite(b)) and b[0] < b[2] and b[1] < b[3], f"bounds {b} is not a rectangle")
        h = hashlib.sha256()
        for d in static + dynamic:
            h.update(d.path.encode())
            h.update(np.ascontiguousarray(d.points, dtype=float).tobytes())
        events = tuple((e.t_ns, e.kind, e.subject, e.part) for e in plant.events)
        return (start, dict(plant.sensors), plant.now_ns, events, h.hexdigest()), len(static) + len(dynamic)

    first, _ = run()
    second, n_draw = run()
    names = ("sensors after reset", "sensors at the end", "now_ns", "events", "geometry")
    for name, a, b in zip(names, first, second):
        need(a == b, f"two runs with seed {seed} differ in {name}: {a!r} != {b!r}")
    plant.reset(seed=seed)
    if problems:
        raise AssertionError(f"check_plant({getattr(plant, 'name', plant)!r}):\n  " + "\n  ".join(problems))
    digest = hashlib.sha256(repr(second).encode()).hexdigest()
    return {"signals": len(signals), "events": len(second[3]), "drawables": n_draw, "digest": digest}


def _check_declarations(plant: Any, need: Any) -> None:
    """The plant's declarations: events, capabilities (declared iff their members are there), rig verbs."""
    from plcsim.scenario.verbs import RigVerb

    events = getattr(plant, "EVENTS", None)
    ok = isinstance(events, (set, frozenset)) and all(isinstance(k, str) and k for k in events)
    need(ok, f"EVENTS must be a set of event kinds, not {events!r}")
    declared = getattr(plant, "CAPABILITIES", None)
    if not isinstance(declared, (set, frozenset)):
        need(False, f"CAPABILITIES must be a frozenset of {sorted(CAPABILITY_MEMBERS)}, not {declared!r}")
        declared = frozenset()
    for cap in sorted(declared):
        members = CAPABILITY_MEMBERS.get(cap)
        if members is None:
            need(False, f"unknown capability {cap!r}; capabilities: {sorted(CAPABILITY_MEMBERS)}")
            continue
        missing = [m for m in members if not hasattr(plant, m)]
        need(not missing, f"declares {cap!r} but lacks {missing}")
    traced = getattr(plant, "TRACED_OBSERVABLES", ())
    if traced and OBSERVABLES in declared:
        values = plant.observables()
        sample = plant.sample_observables()
        need(set(traced) <= set(values), f"TRACED_OBSERVABLES {list(traced)} are not all among observables()")
        need(
            len(sample) == len(traced) and all(isinstance(v, float) for v in sample),
            f"sample_observables() must give {len(traced)} floats, one per TRACED_OBSERVABLES, not {sample!r}",
        )
        need(all(values.get(n) == v for n, v in zip(traced, sample)), "sample_observables() != observables()")
    verbs = getattr(plant, "VERBS", None)
    if not isinstance(verbs, Mapping):
        need(False, f"VERBS must be a mapping of rig verbs (empty if none), not {verbs!r}")
        return
    for key, verb in verbs.items():
        if not isinstance(verb, RigVerb) or verb.name != key:
            need(False, f"VERBS[{key!r}] is not a RigVerb named {key!r}")
        elif not callable(getattr(plant, verb.method, None)):
            need(False, f"rig verb {key!r} calls {verb.method!r}, which the plant does not have")
