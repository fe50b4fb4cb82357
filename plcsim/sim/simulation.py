"""The scheduler: one CPU, one plant, its wiring and a scenario on the one integer clock.

Order of work in each physics step ``[t, t + dt)`` (fixed and documented, so runs are reproducible):

1. scenario actions due at ``t`` (operator presses, parts placed, HMI writes, faults injected);
2. the wiring copies the sensors' electrical levels (the plant state at ``t``) to the input terminals;
3. the CPU runs every PLC event of the step: task starts in ``[t, t + dt)`` (reading the inputs of
   step 2) with their networks and interrupts, and the ends of executions up to ``t + dt``;
4. the plant advances by ``dt``; its events are recorded; geometry is sampled at 25 Hz;
5. outputs that changed (written up to ``t + dt``) go to the actuators, for the next step;
6. actions waiting for a plant condition (``when=held("S2", "1s")``) are armed or fired.

A scan that ends at ``t + dt`` therefore drives the plant from ``t + dt`` on, never earlier, and an
action at ``t`` is seen by the scans that start at ``t`` and by no earlier one.
Same seed, program and scenario give the same trace bit for bit, in any process: nothing here
reads the wall clock (real-time pacing is a subclass that only sleeps).

>>> from plcsim import CPU, Tag
>>> cpu = CPU(tags={"TL": Tag("%I0.0"), "LED": Tag("%Q0.0")}, program="def OB1(t):\\n    t.LED = t.TL\\n")
>>> sim = Simulation(cpu)
>>> sim.run("10ms")
>>> sim.now, sim.cpu.scan_count, len(sim.trace)
(10000000, 10, 10)
"""

from __future__ import annotations

import random
import time
from collections.abc import Callable, Sequence
from operator import itemgetter
from pathlib import PurePath
from typing import Any, Protocol

from plcsim.controllers.protocol import RUN, Controller
from plcsim.core.clock import NEVER
from plcsim.core.errors import ConfigurationError, PlcError
from plcsim.core.literals import format_ns, to_ns
from plcsim.plant.protocol import QUIESCENCE, Plant, capable, stations_of, traced_observables
from plcsim.scenario.names import check_names, controller_verb_problems, plant_vocabulary
from plcsim.scenario.planning import Scenario
from plcsim.scenario.runner import ActionRunner
from plcsim.scenario.verbs import ScenarioError
from plcsim.sim.recorder import Recorder
from plcsim.sim.stepping import fused_step
from plcsim.sim.wiring import Wire, Wiring
from plcsim.trace.facade import Trace, TraceEvent


class SimulationError(PlcError):
    """The plant failed (a physics error, an impossible action); the trace up to it is kept."""


class Simulation:
    """Run a CPU against a plant on one clock.

    Args:
        cpu: the CPU (any :class:`~plcsim.controllers.protocol.Controller`: the S7-1200, the Tecomat), its
            program loaded.
        plant: the machine (None: PLC only, inputs driven by the scenario or by hand).
        wiring: a :class:`Wiring`, or the wires to build one.
        scenario: the operator's actions and the faults.
        dt: physics step (default 1 ms); the scan may be a whole multiple of it.
        seed: seed of placement noise, random times, chatter and analog noise.
        signals: what the trace records (default: every tag; see :mod:`plcsim.sim.recorder`).
        geometry_hz: how often the plant's shapes are sampled for drawing (0: never).
        changes_only: record a trace row only when a value changed (hours-long runs).
        fast_forward: skip physics steps while the plant is quiescent (see :meth:`_skip_quiet`).
        pacing: how the run keeps pace with the wall clock: None (as fast as it goes) or
            :class:`Realtime` (``pacing=Realtime(2.0)``: twice as fast as real time).
    """

    def __init__(
        self,
        cpu: Controller,
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
        pacing: Pacing | None = None,
    ):
        self.pacing = pacing
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
        self.recorder = Recorder(cpu, signals, changes_only=changes_only, observed=traced_observables(plant))
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
        self._frame_still = False
        self._out_version = -1
        self.paused = False
        self.fast_forward = fast_forward
        self._diag_last = cpu.diagnostics[-1] if cpu.diagnostics else None
        self._downloads = getattr(cpu, "downloads", 0)
        """The CPU's download count the recorder is attached for (a download builds new tags to read)."""
        if scenario is not None:
            self._check_scenario(scenario)
        self.actions = ActionRunner(scenario, self.rng, plant, cpu, self.wiring, self.trace)
        for warning in cpu.warnings:
            self.trace.add_event(TraceEvent(self.now, "cpu", "warning", detail=self._portable(warning)))

    def _portable(self, message: str) -> str:
        """A CPU message as the trace keeps it: the program file named without its folders, so that a run's
        trace is the same bit for bit wherever the file sits (a grader's scratch folder, another machine)."""
        filename = str(getattr(getattr(self.cpu, "program", None), "filename", "") or "")
        name = PurePath(filename).name
        return message.replace(filename, name) if name and name != filename else message

    def _check_scenario(self, scenario: Scenario) -> None:
        plant = self.plant
        stations = list(stations_of(plant))
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
            sensors=sensors,
            **plant_vocabulary(plant),
        )
        for problem in controller_verb_problems(scenario, self.cpu):
            raise ScenarioError(": ".join(problem))

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
            end = NEVER
        self._paced(end, condition, progress)
        self._finish()

    def run_until(self, condition: Callable[[Simulation], bool], timeout: str | int = "60s") -> bool:
        """Run until ``condition(sim)`` holds; returns False if ``timeout`` passed first."""
        self._paced(self.now + to_ns(timeout, "timeout"), condition, None)
        self._finish()
        return bool(condition(self))

    def scan(self, count: int = 1) -> None:
        """Run until ``count`` more OB1 scans have ended (physics advancing as needed)."""
        target = self.cpu.scan_count + count
        self._paced(NEVER, lambda sim: sim.cpu.scan_count >= target or sim.cpu.mode != RUN, None)

    def step(self) -> None:
        """One physics step."""
        self._paced(self.now + self.dt_ns, None, None)

    def pause(self) -> None:
        """Make a running :meth:`run` return at the next step (call from a condition or another thread)."""
        self.paused = True

    def resume(self) -> None:
        """Allow running again after :meth:`pause`."""
        self.paused = False

    def _paced(
        self, end_ns: int, condition: Callable[[Simulation], bool] | None, progress: Callable[[int, int], None] | None
    ) -> None:
        if self.pacing is None:
            self._advance(end_ns, condition, progress)
        else:
            self.pacing.advance(self, end_ns, condition, progress)

    def _advance(
        self, end_ns: int, condition: Callable[[Simulation], bool] | None, progress: Callable[[int, int], None] | None
    ) -> None:
        cpu, plant, wiring, actions, trace = self.cpu, self.plant, self.wiring, self.actions, self.trace
        inputs = cpu.inputs
        run_cpu = cpu.run_until
        plant_step = plant.step if plant is not None else None
        events = plant.events if plant is not None else []
        sensors = plant.sensors if plant is not None else {}
        quiet = plant.quiescent if self.fast_forward and capable(plant, QUIESCENCE) else None
        dt = self.dt_ns
        t = start = self.now
        report_every = max(dt, (end_ns - t) // 200) if progress is not None and end_ns < NEVER else NEVER
        next_report = t if progress is not None else NEVER
        frame_ns = self._frame_ns
        if wiring is not None and cpu.output_version != self._out_version:  # the outputs as the run starts
            self._out_version = cpu.output_version
            wiring.write_outputs(cpu.outputs)
        # what the loop compares in every step, as locals (written back to self where they change)
        out_version, diag_last = self._out_version, self._diag_last
        next_frame = self._next_frame if frame_ns else NEVER  # (one comparison per step instead of two)
        diagnostics = cpu.diagnostics
        fused = fused_step(cpu, wiring, self.recorder)
        watch, seen, poll_due = len, None, t  # (the first step polls)
        try:
            while t < end_ns and not self.paused:
                if t >= actions.next_due:
                    actions.apply_due(t)
                    poll_due = t  # (an action may have changed the triggers or the next action's time: poll)
                    self._frame_still = False  # an operator's action may change the picture of a still machine
                    if getattr(cpu, "downloads", 0) != self._downloads:  # a scenario's download: read the new tags
                        self._downloads = cpu.downloads
                        self.recorder.detach()
                        self.recorder.attach()
                    fused = fused_step(cpu, wiring, self.recorder)  # (a fault or a download may have come)
                until = t + dt
                if fused is None or not fused(until):  # (the fused step: wiring in, the scan and its row in one call)
                    if wiring is not None:
                        wiring.step_inputs(inputs, t)
                    run_cpu(until)
                elif cpu.mode != RUN:  # the scan stopped the CPU: the rest of the step as the CPU's run_until goes
                    run_cpu(until)  # on after its fused scan
                if cpu.mode != RUN:
                    self.recorder.on_stopped(t, until)
                if diagnostics and diagnostics[-1] is not diag_last:  # (a length stops growing at the buffer's cap)
                    diag_last = self._cpu_events()
                if plant_step is not None:
                    try:
                        plant_step(dt)
                    except Exception as exc:  # a plant failure is reported, the trace kept
                        trace.add_event(TraceEvent(t, "plant", "plant fault", plant.name, None, str(exc)))
                        raise SimulationError(
                            f"the plant {plant.name} failed at {format_ns(t)}: {type(exc).__name__}: {exc}; "
                            f"the trace up to this moment is kept"
                        ) from exc
                    if events:
                        trace.add_plant_events(events)
                        actions.on_events(events)
                        poll_due = t  # (an event trigger may have scheduled an action)
                        events.clear()
                        self._frame_still = False  # something happened on a still machine: draw it
                if cpu.output_version != out_version:
                    out_version = self._out_version = cpu.output_version
                    if wiring is not None:
                        wiring.write_outputs(cpu.outputs)
                t = until
                self.now = t
                if t >= next_frame:
                    self._sample_frame(t, quiet)
                    next_frame = self._next_frame
                if actions.polled and (t >= poll_due or watch(sensors) != seen):  # (else a poll does nothing: _poll)
                    watch, seen, poll_due = self._poll(t, sensors)
                    fused = fused_step(cpu, wiring, self.recorder)  # (an action may have come)
                if quiet is not None and cpu.mode == RUN and quiet():
                    t = self._skip_quiet(t, end_ns)
                    if frame_ns:
                        next_frame = self._next_frame
                if t >= next_report:
                    progress(t - start, end_ns - start)  # type: ignore[misc]
                    next_report = t + report_every
                if condition is not None and condition(self):
                    break
        finally:
            self.now = t

    def _poll(self, t: int, sensors: dict[str, Any]) -> tuple[Callable[[Any], Any], Any, int]:
        """Poll the scenario's sensor triggers at ``t``; returns a getter of the sensors they watch, what it read
        as the poll compared them, and when the next poll is due whatever the sensors do (an armed trigger's
        time, the next timed action's). Until then a poll would change nothing while the getter reads the same:
        each trigger is armed or not as its sensor was, none is due to fire, no action is due. The loop polls
        after each action and plant event (they may change the triggers or the timed actions), and in the next
        step when this poll changed the triggers or when a trigger watches a sensor the plant lacks."""
        actions = self.actions
        polled = actions.polled
        names = [item.action.when.signal for item in polled]  # type: ignore[union-attr]
        watch: Callable[[Any], Any] = itemgetter(*names)
        seen = watch(sensors) if all(name in sensors for name in names) else None
        actions.poll(t, sensors)
        if seen is None or actions.polled is not polled:
            return watch, seen, t
        return watch, seen, actions.next_time()

    def _sample_frame(self, t: int, quiet: Callable[[], bool] | None) -> None:
        """Record the plant's shapes; a quiescent plant looks the same as at its last frame, so one is enough
        (unless something happened in it since: a part placed on or taken from a still table)."""
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
        if self.wiring is not None and self.wiring.faults:
            return t
        nxt = min(self.cpu.next_event_ns(), self.actions.next_time(), end_ns)
        # land on the step whose window still holds ``nxt``: a step at ``s`` runs the ends of executions
        # up to ``s + dt``, so an execution ending at ``nxt`` belongs to the step before it
        steps = (nxt - t - 1) // self.dt_ns
        if steps > 1:
            self.plant.step(steps * self.dt_ns)  # type: ignore[union-attr]
            t += steps * self.dt_ns
            self.now = t
            self._next_frame = max(self._next_frame, t)
        return t

    def _finish(self) -> None:
        diagnostics = self.cpu.diagnostics
        if diagnostics and diagnostics[-1] is not self._diag_last:  # entered after the last step's look
            self._cpu_events()
        self.trace.meta["end_ns"] = self.now
        self.trace.meta["scans"] = self.cpu.scan_count

    def _cpu_events(self) -> Any:
        """Trace the CPU's diagnostics entered since the last one traced; returns the newest entry.

        The CPU keeps its last 1000 entries (a bounded buffer), so the new ones are those after the last
        traced entry, not after a count."""
        entries = list(self.cpu.diagnostics)
        start = 0
        for i in range(len(entries) - 1, -1, -1):
            if entries[i] is self._diag_last:
                start = i + 1
                break
        for entry in entries[start:]:
            where = entry.task or ""
            if entry.network:
                where += f" network {entry.network}"
            self.trace.add_event(
                TraceEvent(entry.time_ns, "cpu", entry.event, where, None, self._portable(entry.message))
            )
        self._diag_last = entries[-1] if entries else None
        return self._diag_last


class Pacing(Protocol):
    """How a simulation keeps pace with the outside world: it runs the steps through ``sim._advance``."""

    def advance(
        self,
        sim: Simulation,
        end_ns: int,
        condition: Callable[[Simulation], bool] | None,
        progress: Callable[[int, int], None] | None,
    ) -> None: ...


class Realtime:
    """Pacing to the wall clock × ``factor`` (2.0: twice as fast; 0.5: half speed).

    Only the pacing reads the wall clock; the simulated results are identical to an unpaced run (it
    runs the same steps, in chunks of 20 ms of simulated time, and sleeps between them).
    """

    def __init__(self, factor: float = 1.0):
        if factor <= 0:
            raise ConfigurationError(f"realtime factor {factor} must be positive")
        self.factor = factor

    def advance(
        self,
        sim: Simulation,
        end_ns: int,
        condition: Callable[[Simulation], bool] | None,
        progress: Callable[[int, int], None] | None,
    ) -> None:
        """Run ``sim`` up to ``end_ns`` (or the condition), no faster than the wall clock allows."""
        chunk = max(sim.dt_ns, 20_000_000)
        wall0, sim0 = time.perf_counter(), sim.now
        while sim.now < end_ns and not sim.paused:
            sim._advance(min(end_ns, sim.now + chunk), condition, progress)
            if condition is not None and condition(sim):
                break
            ahead = (sim.now - sim0) / 1e9 / self.factor - (time.perf_counter() - wall0)
            if ahead > 0:
                time.sleep(ahead)


class RealtimeSimulation(Simulation):
    """A simulation paced to the wall clock × ``factor``: ``Simulation(..., pacing=Realtime(factor))``."""

    def __init__(self, *args: Any, factor: float = 1.0, **kwargs: Any):
        super().__init__(*args, pacing=Realtime(factor), **kwargs)

    @property
    def factor(self) -> float:
        """The pace: simulated seconds per wall-clock second."""
        return self.pacing.factor  # type: ignore[union-attr]

    @factor.setter
    def factor(self, factor: float) -> None:
        self.pacing = Realtime(factor)
