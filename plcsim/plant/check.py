"""``check_plant``: whether a machine model keeps the Plant protocol (:mod:`plcsim.plant.protocol`), every problem
found listed in one ``AssertionError``.

It needs no CPU, so a rig's tests run it on the model alone; it runs the model twice with one seed, so a model
that is not deterministic is caught too.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np

from plcsim.plant.protocol import (
    CAPABILITY_MEMBERS,
    OBSERVABLES,
    OPERATOR,
    Drawable,
    Plant,
    PlantEvent,
    SignalSpec,
    Station,
    capable,
    missing_members,
    stations_of,
)
from plcsim.plant.verbs import RigVerb


def check_plant(plant: Plant, *, seed: int = 1234, steps: int = 300, dt_ns: int = 1_000_000) -> dict[str, Any]:
    """Check that ``plant`` keeps the protocol; raise ``AssertionError`` listing every problem found.

    Independent of the CPU. It runs the same short exercise twice after ``reset(seed=seed)`` (every operator control
    switched on, then every boolean actuator on, a part placed at the first station if there is one, ``steps`` steps
    of ``dt_ns``, operator controls off again) and checks:

    * the declared signals: names match their keys, directions and kinds are valid, every sensor is in
      ``plant.sensors`` and ``plant.sensors`` holds nothing undeclared (so every declared signal is a sensor there or
      an actuator); stations are :class:`Station` objects under their own names;
    * the declarations: ``EVENTS`` is a set of strings; every capability in ``CAPABILITIES`` is known and the plant
      has its members; every rig verb in ``VERBS`` is a :class:`~plcsim.plant.verbs.RigVerb` under its own name whose
      method the plant has;
    * ``reset`` gives time 0, no events and the same sensors; ``operate`` sets operator sensors;
    * every ``step`` advances ``now_ns`` by exactly ``dt_ns``;
    * events are :class:`PlantEvent` with integer times in ``[0, now_ns]``, in time order, of a declared kind and
      about a declared subject (or a part);
    * drawables have ``(N, 2)`` finite float points (N ≥ 3 for polygons, ≥ 2 for lines, 1 for circles and labels),
      RGB colours and a path; ``bounds`` is a proper rectangle;
    * both runs give identical sensors, events and geometry (determinism);
    * a part placed at the first station, where a belt is drawn (a static polygon ``belt/...``), is carried: some
      actuator, switched on alone, moves it (a top-view rig whose belt does not carry its parts fails here).

    Returns a summary: ``{"signals", "events", "drawables", "digest"}`` (digest = sha256 of the second run).
    """
    import hashlib

    problems: list[str] = []

    def need(cond: bool, msg: str) -> None:
        if not cond:
            problems.append(msg)

    lacking = missing_members(plant, Plant)
    need(not lacking, f"{type(plant).__name__} lacks {', '.join(f'`{m}`' for m in lacking)} of the Plant protocol")
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
    if not problems:
        _check_carried(plant, need, seed=seed, steps=steps, dt_ns=dt_ns)
    plant.reset(seed=seed)
    if problems:
        raise AssertionError(f"check_plant({getattr(plant, 'name', plant)!r}):\n  " + "\n  ".join(problems))
    digest = hashlib.sha256(repr(second).encode()).hexdigest()
    return {"signals": len(signals), "events": len(second[3]), "drawables": n_draw, "digest": digest}


def _check_declarations(plant: Any, need: Any) -> None:
    """The plant's declarations: events, capabilities (declared iff their members are there), rig verbs."""
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


CARRIED_MM = 1.0
"""How far a part on a running belt must move in the check's run to count as carried."""


def _check_carried(plant: Any, need: Any, *, seed: int, steps: int, dt_ns: int) -> None:
    """A part placed at the first station, where a belt is drawn, moves when some actuator alone is switched on."""
    stations = stations_of(plant)
    if not stations:
        return
    station = next(iter(stations.values()))
    belts = [d.path for d in plant.static_drawables() if d.path.startswith("belt/") and _under(plant, station, d)]
    actuators = [k for k, s in plant.signals.items() if s.direction == "actuator" and s.kind == "bool"]
    if not belts or not actuators:
        return
    moved = 0.0
    for name in actuators:
        plant.reset(seed=seed)
        plant.actuate(name, True)
        pid = plant.place(station.name)
        start = _part_centre(plant, pid)
        for _ in range(steps):
            plant.step(dt_ns)
        end = _part_centre(plant, pid)
        if start is None or end is None:
            return  # a part not drawn as parts/<id>: nothing to measure it by
        moved = max(moved, float(np.hypot(*(end - start))))
        if moved >= CARRIED_MM:
            return
    need(
        False,
        f"a part placed at station {station.name!r} lies on {belts[0]}, but no actuator switched on moves it "
        f"({moved:.2f} mm in {steps * dt_ns / 1e9:g} s): the belt does not carry its parts. In a top-view rig, list "
        f"the belt (plants.components.TopBelt, or a component with carrier_at()) among the components, and do not "
        f"override support_at() unless it returns the belt's body",
    )


def _under(plant: Any, station: Station, belt: Drawable) -> bool:
    """Whether a part at ``station`` lies on the drawn belt (a side view: above its length; a top view: on it)."""
    if belt.kind != "polygon":
        return False
    (x0, y0), (x1, y1) = belt.points.min(axis=0), belt.points.max(axis=0)
    return x0 <= station.x <= x1 and (getattr(plant, "view", "") == "side" or y0 <= station.y <= y1)


def _part_centre(plant: Any, pid: str) -> np.ndarray | None:
    for d in plant.dynamic_drawables():
        if d.path == f"parts/{pid}":
            return np.asarray(d.points, dtype=float).mean(axis=0)
    return None
