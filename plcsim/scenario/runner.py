"""Carrying out a scenario during a run: the operator's actions at their times or when the plant asks.

An action the plant's state makes impossible (removing a part that has fallen off, placing one where
another lies) is the run's business: it is recorded as an ``action failed`` event and the run goes on.
An action that could never work (a button, tag or fault the exercise lacks, a value its tag refuses)
is the instructor's mistake: it raises :class:`~plcsim.core.errors.ExerciseError`, never touching the
student's trace; anything else is a bug of ours and propagates as it is.

Timed actions wait in a queue ordered by time. An action waiting for the plant (``when=held("S2",
"1s")`` or ``when=after_event(...)``) joins the queue once its trigger fires; an action on a part
waits until that part has been placed. Only the sensor triggers that can fire now are polled in each
physics step, so a long scenario costs nothing while it waits.
"""

from __future__ import annotations

import random
from bisect import insort
from collections.abc import Callable
from pathlib import PureWindowsPath
from typing import Any

from plcsim.core.clock import NEVER
from plcsim.core.errors import ConfigurationError, ExerciseError, PlcError
from plcsim.plant.protocol import MOTOR_JAM, SENSOR_SHIFT, capable, rig_verbs, stations_of
from plcsim.scenario.planning import Planned, Scenario, plan
from plcsim.scenario.verbs import Action, OneOf, ScenarioError
from plcsim.trace.facade import Trace, TraceEvent

POSE_NOISE_MM = 5.0
POSE_NOISE_DEG = 5.0
PART_VERBS = {"remove", "jam", "unjam", "knock_off"}
STATE_VERBS = PART_VERBS | {"place", "stop_cpu", "start_cpu", "power_cycle", "download"}
"""Verbs whose failure can depend on the run (a part gone, a station taken): recorded, not raised."""


class ActionRunner:
    """The scenario's timeline during one run."""

    def __init__(self, scenario: Scenario | None, rng: random.Random, plant: Any, cpu: Any, wiring: Any, trace: Trace):
        self.plant, self.cpu, self.wiring, self.trace, self.rng = plant, cpu, wiring, trace, rng
        self.parts: dict[str, str] = {}
        self._timed: list[tuple[int, int, Action]] = []
        self._held: list[Planned] = []  # sensor triggers, not fired yet
        self._on_event: list[Planned] = []  # event triggers, not fired yet
        self.polled: list[Planned] = []  # the sensor triggers that can fire now
        self._polls: list[tuple[Planned, str, Any, int]] = []
        self._scenario_parts: set[str] = set()
        if scenario is not None:
            self._scenario_parts = {a.target for a in scenario.actions if a.verb == "place"}
            for item in plan(scenario, rng):
                if item.at_ns is not None:
                    self._timed.append((item.at_ns, item.order, item.action))
                elif item.action.when.signal is not None:  # type: ignore[union-attr]
                    self._held.append(item)
                else:
                    self._on_event.append(item)
            self._timed.sort(key=lambda e: (e[0], e[1]))
            self._refresh_polled()
        self.next_due = self._timed[0][0] if self._timed else NEVER

    # -- what can happen when -------------------------------------------------------------------

    def _ready(self, item: Planned) -> bool:
        action = item.action
        return not (_on_part(action) and action.target in self._scenario_parts and action.target not in self.parts)

    def _refresh_polled(self) -> None:
        self.polled = [item for item in self._held if self._ready(item)]
        # what poll() compares for each, looked up once (it runs after every physics step)
        self._polls = [
            (item, item.action.when.signal, item.action.when.value, item.action.when.for_ns) for item in self.polled
        ]  # type: ignore[union-attr]

    def _schedule(self, item: Planned, at_ns: int) -> None:
        insort(self._timed, (at_ns, item.order, item.action), key=lambda e: (e[0], e[1]))
        self.next_due = self._timed[0][0]

    def next_time(self) -> int:
        """The earliest time something scheduled or armed will happen."""
        due = self.next_due
        for item in self.polled:
            if item.armed_since is not None:
                due = min(due, item.armed_since + item.action.when.for_ns)  # type: ignore[union-attr]
        return due

    def schedule(self, action: Action, at_ns: int, order: int) -> None:
        """Add a timed action during the run (a live session's click), applied at the first step starting at or
        after ``at_ns``; ``order`` breaks ties as an action's place in a scenario does."""
        self._schedule(Planned(action, at_ns, order), at_ns)

    # -- during the run ---------------------------------------------------------------------------

    def apply_due(self, t: int) -> None:
        """Carry out every action due at or before ``t``, in time order."""
        timed = self._timed
        while timed and timed[0][0] <= t:
            self.apply(timed.pop(0)[2], t)
        self.next_due = timed[0][0] if timed else NEVER

    def poll(self, t: int, sensors: dict[str, Any]) -> None:
        """Arm or fire the sensor triggers that can fire now (called after every physics step)."""
        fired = False
        for item, signal, value, for_ns in self._polls:
            if sensors.get(signal) == value:
                if item.armed_since is None:
                    item.armed_since = t
                if t - item.armed_since >= for_ns:
                    self._held.remove(item)
                    self._schedule(item, t + item.action.delay.draw(self.rng))
                    fired = True
            else:
                item.armed_since = None
        if fired:
            self._refresh_polled()
        if self.next_due <= t:
            self.apply_due(t)

    def on_events(self, events: list[Any]) -> None:
        """Fire the event triggers that these plant events satisfy."""
        if not self._on_event:
            return
        for item in list(self._on_event):
            if not self._ready(item):
                continue
            trig = item.action.when
            for e in events:
                if e.kind == trig.event and (trig.subject is None or trig.subject in (e.subject, e.part)):  # type: ignore[union-attr]
                    self._on_event.remove(item)
                    self._schedule(item, e.t_ns + item.action.delay.draw(self.rng))
                    break

    def apply(self, action: Action, t: int) -> None:
        """Carry out one action; one the run made impossible (a part that fell off) is recorded, never raised.

        Raises:
            ExerciseError: the action could never work in this exercise (the instructor's mistake).
        """
        verb = action.verb
        try:
            detail = self._carry_out(action)
        except ExerciseError:
            raise
        except (PlcError, KeyError, ValueError) as exc:
            reason = exc.args[0] if isinstance(exc, KeyError) and exc.args else str(exc)
            where = f"{action.describe()} ({_file_name(action.defined_at)})"  # the trace names no folder
            if verb not in STATE_VERBS and not (action.rig is not None and action.rig.state):
                raise ExerciseError(f"{action.defined_at}: {action.describe()}: {reason}") from exc
            if _on_part(action) and action.target in self.parts:
                reason = f"{action.target} is no longer in the plant ({reason})"
            self.trace.add_event(TraceEvent(t, "scenario", "action failed", action.target, None, f"{where}: {reason}"))
            return
        plant = self.plant
        if plant is not None and plant.events:
            self.trace.add_plant_events(plant.events)
            self.on_events(plant.events)
            plant.events.clear()
        self.trace.add_event(TraceEvent(t, "scenario", verb, action.target, self.parts.get(action.target), detail))

    def _carry_out(self, action: Action) -> str:
        """Do what the action says; returns the detail for the trace event."""
        plant, cpu = self.plant, self.cpu
        verb, target, args = action.verb, action.target, action.args
        detail = ""
        if action.rig is not None and action.rig.controller:
            if action.rig is not getattr(cpu, "VERBS", {}).get(verb):
                raise ExerciseError(f"{action.defined_at}: {action.describe()}: the controller does not bring it")
            detail = getattr(cpu, action.rig.method)(target, **args) or ""
        elif action.rig is not None:
            if action.rig is not rig_verbs(plant).get(verb):
                raise ConfigurationError(f"the plant {getattr(plant, 'name', None)} does not bring the verb {verb!r}")
            getattr(plant, action.rig.method)(self.parts.get(target, target), **args)
        elif verb == "place":
            if args["station"] not in stations_of(plant):  # not the run's doing: never possible
                station = args["station"]
                raise ScenarioError(f"{action.defined_at}: {action.describe()}: there is no station {station!r}")
            offset, angle = (
                self.rng.uniform(*v) if isinstance(v, tuple) else v for v in (args["offset_mm"], args["angle_deg"])
            )
            if args["noise"]:
                offset = self.rng.uniform(-POSE_NOISE_MM, POSE_NOISE_MM) if offset is None else offset
                angle = self.rng.uniform(-POSE_NOISE_DEG, POSE_NOISE_DEG) if angle is None else angle
            properties = {k: v.draw(self.rng) if isinstance(v, OneOf) else v for k, v in args["properties"].items()}
            self.parts[target] = plant.place(
                args["station"], part=target, offset_mm=offset or 0.0, angle_deg=angle or 0.0, **properties
            )
            detail = f"offset {offset or 0.0:+.2f} mm, angle {angle or 0.0:+.2f} deg"
            self._refresh_polled()
        elif verb == "remove":
            plant.remove(self.parts.get(target, target))
        elif verb in ("jam", "unjam", "knock_off"):
            method = {"jam": plant.hold, "unjam": plant.release, "knock_off": plant.knock_off}[verb]
            method(self.parts.get(target, target))
        elif verb in ("press", "release", "switch"):
            value = args["on"] if verb == "switch" else verb == "press"
            if plant is None:
                cpu.set_input(target, value)
            else:
                plant.operate(target, value)
        elif verb == "write":
            cpu.write(target, args["value"])
            detail = f"= {args['value']!r}"
        elif verb == "force":
            cpu.force(target, args["value"])
            detail = f"= {args['value']!r}"
        elif verb == "unforce":
            cpu.unforce(target)
        elif verb in ("stick", "break_wire", "chatter", "clear"):
            self._wiring_fault(verb, target, args)
        elif verb == "shift":
            _plant_method(plant, "shift_sensor", SENSOR_SHIFT)(target, args["mm"])
        elif verb in ("jam_motor", "free_motor"):
            _plant_method(plant, "jam_motor", MOTOR_JAM)(target, verb == "jam_motor")
        elif verb == "stop_cpu":
            cpu.stop(reason="mode switch")
        elif verb == "start_cpu":
            cpu.start()
        elif verb == "power_cycle":
            cpu.power_cycle()
        elif verb == "download":
            load = getattr(cpu, "download", None)
            if load is None:
                raise ScenarioError(f"{type(cpu).__name__} takes no download in a scenario")
            load(args["program"], args.get("file") or "<downloaded program>")
            detail = args.get("file") or ""
        else:  # pragma: no cover - the constructors make only the verbs above
            raise ScenarioError(f"unknown action {verb!r}")
        return detail

    def _wiring_fault(self, verb: str, target: str, args: dict[str, Any]) -> None:
        wiring = self.wiring
        if wiring is None:
            raise ConfigurationError("this run has no wiring to put a fault in")
        if verb == "stick":
            wiring.stick(target, args["value"])
        elif verb == "break_wire":
            wiring.break_wire(target)
        elif verb == "chatter":
            wiring.chatter(target, args["transitions"], args["width"])
        else:
            wiring.clear(target)


def _plant_method(plant: Any, method: str, capability: str) -> Callable[..., Any]:
    """The plant's method for a verb; the plant must declare the capability it belongs to."""
    if not capable(plant, capability):
        raise ConfigurationError(f"the plant {getattr(plant, 'name', None)} does not declare {capability!r}")
    return getattr(plant, method)


def _on_part(action: Action) -> bool:
    """Whether the action's target is a part of the scenario."""
    return action.verb in PART_VERBS or (action.rig is not None and action.rig.on_parts)


def _file_name(defined_at: str) -> str:
    r"""The place an action was written, without its folders (either separator), so that a trace is the same
    bit for bit wherever the exercise file sits (another checkout, another machine).

    >>> _file_name("/any/folder/ex_6_3_01.py:42"), _file_name("C:\\course\\ex_9.py:7")
    ('ex_6_3_01.py:42', 'ex_9.py:7')
    """
    file, colon, line = defined_at.rpartition(":")
    return f"{PureWindowsPath(file).name}:{line}" if colon and line.isdigit() else PureWindowsPath(defined_at).name
