"""The scheduler: one CPU, one plant, its wiring and a scenario on the one integer clock.

Order of work in each physics step ``[t, t + dt)`` (fixed and documented, so runs are reproducible):

1. scenario actions due at ``t`` (operator presses, parts placed, HMI writes, faults injected);
2. the wiring copies the sensors' electrical levels (the plant state at ``t``) to the input terminals;
3. the CPU runs every PLC event in ``[t, t + dt)``: output writes, task starts (reading the inputs
   of step 2), networks, interrupts;
4. outputs that changed go to the actuators;
5. the plant advances by ``dt``; its events are recorded; geometry is sampled at 25 Hz;
6. actions waiting for a plant condition (``when=held("S2", "1s")``) are armed or fired.

A scan that ends at ``t + dt`` therefore drives the plant from ``t + dt`` on, never earlier.
Same seed, program and scenario give the same trace bit for bit, in any process: nothing here
reads the wall clock (real-time pacing is a subclass that only sleeps).

>>> from plcsim import CPU, Tag
>>> cpu = CPU(tags={"TL": Tag("%I0.0"), "LED": Tag("%Q0.0")}, program="def OB1(t):\\n    t.LED = t.TL\\n")
>>> sim = Simulation(cpu)
>>> sim.run("10ms")
>>> sim.now, sim.cpu.scan_count, len(sim.trace)
(10000000, 9, 9)

(The scan that ends exactly at 10 ms writes its outputs at 10 ms, the first event of the next run.)
"""

from __future__ import annotations

import random
import time
from collections.abc import Callable, Sequence
from typing import Any

from plcsim.cpu import CPU, RUN
from plcsim.errors import ConfigurationError, PlcError
from plcsim.literals import format_ns, to_ns
from plcsim.plant import Plant
from plcsim.recorder import Recorder
from plcsim.scenario import Planned, Scenario, ScenarioError, Trigger, check_names, plan
from plcsim.trace import Trace, TraceEvent
from plcsim.wiring import Wire, Wiring

POSE_NOISE_MM = 5.0
POSE_NOISE_DEG = 5.0


class SimulationError(PlcError):
    """The plant failed (a physics error, an impossible action); the trace up to it is kept."""


class Simulation:
    """Run a CPU against a plant on one clock.

    Args:
        cpu: the CPU, with its program loaded.
        plant: the machine (None: PLC only, inputs driven by the scenario or by hand).
        wiring: a :class:`Wiring`, or the wires to build one.
        scenario: the operator's actions and the faults.
        dt: physics step (default 1 ms); the scan may be a whole multiple of it.
        seed: seed of placement noise, random times, chatter and analog noise.
        signals: what the trace records (default: every tag; see :mod:`plcsim.recorder`).
        geometry_hz: how often the plant's shapes are sampled for drawing (0: never).
        changes_only: record a trace row only when a value changed (hours-long runs).
        fast_forward: skip physics steps while the plant is quiescent (see :meth:`_skip_quiet`).
    """

    def __init__(
        self,
        cpu: CPU,
        plant: Plant | None = None,
        wiring: Wiring | Sequence[Wire] | None = None,
        scenario: Scenario | None = None,
        *,
        dt: str | int = "1ms",
        seed: int = 0,
        signals: Sequence[str] | None = None,
        geometry_hz: float = 25.0,
        changes_only: bool = False,
        fast_forward: bool = True,
    ):
        self.cpu = cpu
        self.plant = plant
        self.seed = seed
        self.dt_ns = to_ns(dt, "dt")
        if self.dt_ns <= 0:
            raise ConfigurationError(f"dt {dt!r} must be positive")
        self.rng = random.Random(seed)
        if plant is not None:
            plant.reset(seed=seed)
        if wiring is None or isinstance(wiring, Wiring):
            self.wiring = wiring
        else:
            if plant is None:
                raise ConfigurationError("wires need a plant")
            self.wiring = Wiring(plant, cpu.table, wiring, seed=seed)
        self.scenario = scenario
        self.now = cpu.clock.now
        self.recorder = Recorder(cpu, signals, changes_only=changes_only)
        self.recorder.attach()
        self.trace: Trace = self.recorder.trace
        self.trace.meta.update(
            {
                "seed": seed,
                "dt_ns": self.dt_ns,
                "cycle_ns": cpu.config.cycle_ns,
                "plant": plant.name if plant else None,
                "scenario": scenario.name if scenario else None,
                "program": cpu.program.filename if cpu.program else None,
                "timer_dialect": str(cpu.config.timer_dialect),
                "rtc_start": cpu.config.rtc_start,
            }
        )
        if plant is not None:
            self.trace.static_drawables = plant.static_drawables()
            self.trace.bounds = plant.bounds()
        self._frame_ns = int(1e9 / geometry_hz) if geometry_hz and plant is not None else 0
        self._next_frame = self.now
        self._out_version = -1
        self._parts: dict[str, str] = {}
        self._planned: list[Planned] = []
        self._waiting: list[Planned] = []
        self._next_action = _NEVER
        self.paused = False
        self.fast_forward = fast_forward
        self._frame_still = False
        self._mode_seen = cpu.mode
        self._diag_seen = len(cpu.diagnostics)
        self._scenario_parts = {a.target for a in scenario.actions if a.verb == "place"} if scenario else set()
        if scenario is not None:
            self._check_scenario(scenario)
            planned = plan(scenario, self.rng)
            self._planned = sorted((p for p in planned if p.at_ns is not None), key=lambda p: (p.at_ns, p.order))
            self._waiting = [p for p in planned if p.at_ns is None]
            self._next_action = self._planned[0].at_ns if self._planned else _NEVER
        for warning in cpu.warnings:
            self.trace.add_event(TraceEvent(self.now, "cpu", "warning", detail=warning))

    # -- checks before the run ------------------------------------------------------------------

    def _check_scenario(self, scenario: Scenario) -> None:
        plant = self.plant
        stations = list(plant.stations) if plant else []
        buttons = [n for n, s in plant.signals.items() if s.operator] if plant else list(self.cpu.inputs)
        sensors = [n for n, s in plant.signals.items() if s.direction == "sensor"] if plant else []
        actuators = [n for n, s in plant.signals.items() if s.direction == "actuator"] if plant else []
        signals = sensors + actuators
        if self.wiring is not None:
            signals += [t for t in self.wiring.by_tag if t not in signals]
        check_names(
            scenario,
            stations=stations,
            buttons=buttons,
            signals=signals,
            tags=[e.name for e in self.cpu.table],
            actuators=actuators,
        )

    # -- running --------------------------------------------------------------------------------

    def run(
        self,
        duration: str | int | None = None,
        *,
        until: str | int | None = None,
        condition: Callable[[Simulation], bool] | None = None,
        progress: Callable[[int, int], None] | None = None,
    ) -> None:
        """Run for ``duration`` (default: the scenario's), or ``until`` an absolute time, or until
        ``condition(sim)`` is true (checked after every step)."""
        if until is not None:
            end = to_ns(until, "until")
        elif duration is not None:
            end = self.now + to_ns(duration, "duration")
        elif self.scenario is not None:
            end = self.scenario.duration_ns
        elif condition is None:
            raise ConfigurationError("give a duration ('10s'), until= or condition=")
        else:
            end = _NEVER
        self._advance(end, condition, progress)
        self._finish()

    def run_until(self, condition: Callable[[Simulation], bool], timeout: str | int = "60s") -> bool:
        """Run until ``condition(sim)`` holds; returns False if ``timeout`` passed first."""
        end = self.now + to_ns(timeout, "timeout")
        self._advance(end, condition, None)
        self._finish()
        return bool(condition(self))

    def scan(self, count: int = 1) -> None:
        """Run until ``count`` more OB1 scans have ended (physics advancing as needed)."""
        target = self.cpu.scan_count + count
        self._advance(_NEVER, lambda sim: sim.cpu.scan_count >= target or sim.cpu.mode != RUN, None)

    def step(self) -> None:
        """One physics step."""
        self._advance(self.now + self.dt_ns, None, None)

    def pause(self) -> None:
        """Make a running :meth:`run` return at the next step (call from a condition or another thread)."""
        self.paused = True

    def resume(self) -> None:
        """Allow running again after :meth:`pause`."""
        self.paused = False

    def _advance(
        self, end_ns: int, condition: Callable[[Simulation], bool] | None, progress: Callable[[int, int], None] | None
    ) -> None:
        cpu, plant, wiring = self.cpu, self.plant, self.wiring
        inputs = cpu.inputs
        dt = self.dt_ns
        t = self.now
        start = t
        next_report = t
        report_every = max(dt, (end_ns - t) // 200) if progress is not None and end_ns < _NEVER else _NEVER
        quiet = getattr(plant, "quiescent", None) if self.fast_forward else None
        try:
            while t < end_ns and not self.paused:
                if t >= self._next_action:
                    self._apply_due(t)
                if wiring is not None:
                    wiring.read_inputs(inputs, t)
                cpu.run_until(t + dt)
                if cpu.output_version != self._out_version:
                    self._out_version = cpu.output_version
                    if wiring is not None:
                        wiring.write_outputs(cpu.outputs)
                if cpu.mode != RUN:
                    self.recorder.on_stopped(t, t + dt)
                if cpu.mode != self._mode_seen or len(cpu.diagnostics) != self._diag_seen:
                    self._cpu_events()
                if plant is not None:
                    try:
                        plant.step(dt)
                    except Exception as exc:
                        self.trace.add_event(TraceEvent(t, "plant", "plant fault", plant.name, None, str(exc)))
                        raise SimulationError(
                            f"the plant {plant.name} failed at {format_ns(t)}: {type(exc).__name__}: {exc}; "
                            f"the trace up to this moment is kept"
                        ) from exc
                    if plant.events:
                        self.trace.add_plant_events(plant.events)
                        if self._waiting:
                            self._events_for_triggers(plant.events)
                        plant.events.clear()
                t += dt
                self.now = t
                if t >= self._next_frame and self._frame_ns:
                    self._sample_frame(t, quiet)
                if self._waiting:
                    self._check_triggers(t)
                if quiet is not None and cpu.mode == RUN and quiet():
                    t = self._skip_quiet(t, end_ns)
                if progress is not None and t >= next_report:
                    progress(t - start, end_ns - start)
                    next_report = t + report_every
                if condition is not None and condition(self):
                    break
        finally:
            self.now = t

    def _sample_frame(self, t: int, quiet: Callable[[], bool] | None) -> None:
        """Record the plant's shapes; a quiescent plant looks the same as at its last frame, so one is enough."""
        still = quiet is not None and quiet()
        if not (still and self._frame_still):
            self.trace.add_frame(t, self.plant.dynamic_drawables())  # type: ignore[union-attr]
        self._frame_still = still
        self._next_frame = t + self._frame_ns

    def _skip_quiet(self, t: int, end_ns: int) -> int:
        """Jump over steps in which provably nothing can change: the plant is quiescent (no part, every
        drive settled, so a step only advances its clock) and no PLC event, scenario action or armed
        trigger falls before the next step boundary we stop at. Scans, actions and triggers then happen
        at exactly the times they would have, so the trace rows and events are the same bit for bit."""
        nxt = min(self.cpu.next_event_ns(), self._next_action, end_ns, self._trigger_due())
        steps = (nxt - t) // self.dt_ns
        if steps > 1 and not (self.wiring is not None and self.wiring.faults):
            self.plant.step(steps * self.dt_ns)  # type: ignore[union-attr]
            t += steps * self.dt_ns
            self.now = t
            self._next_frame = max(self._next_frame, t)
        return t

    def _trigger_due(self) -> int:
        due = _NEVER
        for item in self._waiting:
            if item.at_ns is not None:
                due = min(due, item.at_ns)
            elif item.armed_since is not None:
                due = min(due, item.armed_since + item.action.when.for_ns)  # type: ignore[union-attr]
        return due

    def _finish(self) -> None:
        self.trace.meta["end_ns"] = self.now
        self.trace.meta["scans"] = self.cpu.scan_count

    # -- CPU events ---------------------------------------------------------------------------

    def _cpu_events(self) -> None:
        cpu = self.cpu
        for entry in list(cpu.diagnostics)[self._diag_seen :]:
            where = entry.task or ""
            if entry.network:
                where += f" network {entry.network}"
            self.trace.add_event(TraceEvent(entry.time_ns, "cpu", entry.event, where, None, entry.message))
        self._diag_seen = len(cpu.diagnostics)
        self._mode_seen = cpu.mode

    # -- scenario -----------------------------------------------------------------------------

    def _apply_due(self, t: int) -> None:
        planned = self._planned
        while planned and planned[0].at_ns <= t:  # type: ignore[operator]
            self._apply(planned.pop(0).action, t)
        self._next_action = planned[0].at_ns if planned else _NEVER  # type: ignore[assignment]

    def _apply(self, action: Any, t: int) -> None:
        plant, cpu, wiring = self.plant, self.cpu, self.wiring
        verb, target, args = action.verb, action.target, action.args
        detail = ""
        try:
            if verb == "place":
                offset = args["offset_mm"]
                angle = args["angle_deg"]
                if args["noise"]:
                    offset = self.rng.uniform(-POSE_NOISE_MM, POSE_NOISE_MM) if offset is None else offset
                    angle = self.rng.uniform(-POSE_NOISE_DEG, POSE_NOISE_DEG) if angle is None else angle
                pid = plant.place(
                    args["station"], part=target, offset_mm=offset or 0.0, angle_deg=angle or 0.0, **args["properties"]
                )
                self._parts[target] = pid
                detail = f"offset {offset or 0.0:+.2f} mm, angle {angle or 0.0:+.2f} deg"
            elif verb == "remove":
                plant.remove(self._parts.get(target, target))
            elif verb in ("jam", "unjam", "knock_off"):
                method = {"jam": plant.hold, "unjam": plant.release, "knock_off": plant.knock_off}[verb]
                method(self._parts.get(target, target))
            elif verb in ("press", "release", "switch"):
                value = args["on"] if verb == "switch" else verb == "press"
                if plant is None:
                    cpu.set_input(target, value)
                else:
                    plant.operate(target, value)
            elif verb == "write":
                cpu.write(target, args["value"])
            elif verb == "stick":
                wiring.stick(target, args["value"])
            elif verb == "break_wire":
                wiring.break_wire(target)
            elif verb == "chatter":
                wiring.chatter(target, args["transitions"], args["width"])
            elif verb == "clear":
                wiring.clear(target)
            elif verb == "shift":
                _plant_fault(plant, "shift_sensor")(target, args["mm"])
            elif verb == "jam_motor":
                _plant_fault(plant, "jam_motor")(target, True)
            elif verb == "free_motor":
                _plant_fault(plant, "jam_motor")(target, False)
            elif verb == "stop_cpu":
                cpu.stop(reason="mode switch")
            elif verb == "start_cpu":
                cpu.start()
            elif verb == "power_cycle":
                cpu.power_cycle()
            else:  # pragma: no cover - the constructors make only the verbs above
                raise ScenarioError(f"unknown action {verb!r}")
        except PlcError as exc:
            self.trace.add_event(
                TraceEvent(
                    t, "scenario", "action failed", target, None, f"{action.describe()} ({action.defined_at}): {exc}"
                )
            )
            return
        if self.plant is not None and self.plant.events:
            self.trace.add_plant_events(self.plant.events)
            if self._waiting:
                self._events_for_triggers(self.plant.events)
            self.plant.events.clear()
        self.trace.add_event(TraceEvent(t, "scenario", verb, target, self._parts.get(target), detail))

    def _check_triggers(self, t: int) -> None:
        sensors = self.plant.sensors if self.plant is not None else {}
        for item in list(self._waiting):
            trig: Trigger = item.action.when  # type: ignore[assignment]
            if (
                item.action.verb in _PART_VERBS
                and item.action.target in self._scenario_parts
                and item.action.target not in self._parts
            ):
                continue  # an action on a part waits until the part has been placed
            if item.at_ns is None and trig.signal is not None:
                if sensors.get(trig.signal) == trig.value:
                    if item.armed_since is None:
                        item.armed_since = t
                    if t - item.armed_since >= trig.for_ns:
                        item.at_ns = t + item.action.delay.draw(self.rng)
                else:
                    item.armed_since = None
            if item.at_ns is not None and item.at_ns <= t:
                self._waiting.remove(item)
                self._apply(item.action, t)

    def _events_for_triggers(self, events: list[Any]) -> None:
        for item in self._waiting:
            trig: Trigger = item.action.when  # type: ignore[assignment]
            if (
                item.action.verb in _PART_VERBS
                and item.action.target in self._scenario_parts
                and item.action.target not in self._parts
            ):
                continue
            if item.at_ns is None and trig.event is not None:
                for e in events:
                    if e.kind == trig.event and (trig.subject is None or trig.subject in (e.subject, e.part)):
                        item.at_ns = e.t_ns + item.action.delay.draw(self.rng)
                        break


def _plant_fault(plant: Plant | None, method: str) -> Callable[..., Any]:
    fn = getattr(plant, method, None)
    if fn is None:
        raise ScenarioError(f"the plant {getattr(plant, 'name', None)} does not support {method}")
    return fn


class RealtimeSimulation(Simulation):
    """A simulation paced to the wall clock × ``factor`` (2.0: twice as fast; 0.5: half speed).

    Only the pacing reads the wall clock; the simulated results are identical to :class:`Simulation`.
    """

    def __init__(self, *args: Any, factor: float = 1.0, **kwargs: Any):
        super().__init__(*args, **kwargs)
        if factor <= 0:
            raise ConfigurationError(f"realtime factor {factor} must be positive")
        self.factor = factor

    def _advance(
        self, end_ns: int, condition: Callable[[Simulation], bool] | None, progress: Callable[[int, int], None] | None
    ) -> None:
        chunk = max(self.dt_ns, 20_000_000)
        wall0, sim0 = time.perf_counter(), self.now
        while self.now < end_ns and not self.paused:
            stop = min(end_ns, self.now + chunk)
            super()._advance(stop, condition, progress)
            if condition is not None and condition(self):
                break
            ahead = (self.now - sim0) / 1e9 / self.factor - (time.perf_counter() - wall0)
            if ahead > 0:
                time.sleep(ahead)


_NEVER = 1 << 62
_PART_VERBS = {"remove", "jam", "unjam", "knock_off"}
