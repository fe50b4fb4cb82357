"""The fused step (plcsim.sim.stepping): wiring in, the scan and its trace row in one call gives the trace the
general path gives, bit for bit, and declines every step that holds more than one plain scan.

Each run is compared with the same run on the general path: a CPU configured with ``fuse=False`` has no fused
scan, so its scan loop (``TaskRunner``) and the recorder's hook do every step.
"""

from __future__ import annotations

from collections.abc import Callable

import pytest

from exercises import get
from plants import Panel
from plcsim import CPU, STOP, Simulation, Tag
from plcsim.scenario.planning import Scenario
from plcsim.scenario.verbs import clear, download, held, press, release, start_cpu, stop_cpu, stuck
from plcsim.sim import simulation as simulation_module
from plcsim.sim.wiring import NO

MS = 1_000_000


def both_paths(
    build: Callable[..., Simulation], monkeypatch: pytest.MonkeyPatch
) -> tuple[Simulation, Simulation, list[int]]:
    """The run on the fused path, the same run on the general path (``CPUConfig(fuse=False)``: the CPU's scan
    loop and the recorder's hook do every step), and the steps the fused step did."""
    fused_steps: list[int] = []
    make = simulation_module.fused_step

    def counted(*args):
        step = make(*args)
        if step is None:
            return None

        def counting(until: int) -> bool:
            done = step(until)
            if done:
                fused_steps.append(until - MS)
            return done

        return counting

    monkeypatch.setattr(simulation_module, "fused_step", counted)
    fused = build()
    fused.run()
    steps = list(fused_steps)
    general = build(fuse=False)
    general.run()
    assert fused_steps == steps  # the general run never took the fused step
    return fused, general, steps


def same_run(fused: Simulation, general: Simulation) -> None:
    assert fused.trace.digest() == general.trace.digest()
    assert fused.trace.events == general.trace.events
    assert [f.t_ns for f in fused.trace.frames] == [f.t_ns for f in general.trace.frames]
    assert (fused.now, fused.cpu.scan_count, fused.cpu.mode) == (general.now, general.cpu.scan_count, general.cpu.mode)


def panel(program: str, scenario: Scenario) -> Callable[..., Simulation]:
    def build(**options: bool) -> Simulation:
        cpu = CPU(tags={"TL": Tag("%I0.0"), "LED": Tag("%Q0.0")}, program=program, **options)
        plant = Panel(buttons=("TL",), switches=(), lamps=("LED",))
        return Simulation(cpu, plant, [NO("TL"), NO("LED")], scenario, fast_forward=False)

    return build


def test_an_error_in_a_fused_scan_stops_the_cpu_as_the_general_path_does(monkeypatch):
    program = "N = Int(0)\n\ndef OB1(t):\n    t.N = t.N + 1\n    t.LED = t.TL\n    if t.TL:\n        x = 1 // 0\n"
    scenario = Scenario("s", press("TL", t="10ms"), release("TL", t="20ms"), start_cpu(t="30ms"), duration="50ms")
    fused, general, steps = both_paths(panel(program, scenario), monkeypatch)
    same_run(fused, general)
    assert fused.cpu.read("N") == 20 and fused.cpu.scan_count == 30  # stopped at 10 ms, N from 0 again at 30 ms
    assert "ZeroDivisionError" in fused.trace.events_of("error in the program")[0].detail
    assert steps[:11] == [k * MS for k in range(11)]  # the scan that raised at 10 ms among them
    assert len(steps) > 11 + 15 and steps[11] >= 30 * MS  # the scans after the restart


def test_stop_and_start_by_the_scenario_on_the_fused_path(monkeypatch):
    scenario = Scenario("s", press("TL", t="5ms"), stop_cpu(t="10ms"), start_cpu(t="20ms"), duration="30ms")
    fused, general, steps = both_paths(panel("def OB1(t):\n    t.LED = t.TL\n", scenario), monkeypatch)
    same_run(fused, general)
    assert fused.cpu.mode != STOP and 25 > len(steps) > 15 and 15 * MS not in steps  # the steps in STOP declined


def test_a_fault_a_download_and_a_wiring_fault_from_a_trigger_give_the_general_paths_trace(monkeypatch):
    """A fault in the middle of a scan (STOP, then RUN again), a download into the running CPU (the step builds
    its scan again: new tags, a new plan), and a stuck input that a sensor trigger brings (polled at the step's
    end, so the step that follows runs the faulted wiring through the general path) until a timed clear."""
    first = "N = Int(0)\n\ndef OB1(t):\n    t.N = t.N + 1\n    t.LED = t.TL\n"
    first += "    if t.TL and t.N > 12:\n        x = 1 // 0\n"
    second = "N = Int(0)\nM = Int(0)\n\ndef OB1(t):\n    t.N = t.N + 2\n    t.M = t.M + t.TL\n    t.LED = not t.TL\n"
    scenario = Scenario(
        "s",
        press("TL", t="10ms"),
        release("TL", t="14ms"),
        start_cpu(t="16ms"),
        download(second, t="20ms"),
        press("TL", t="30ms"),
        release("TL", t="38ms"),
        stuck("TL", True, when=held("TL", "5ms")),
        clear("TL", t="40ms"),
        duration="50ms",
    )
    fused, general, steps = both_paths(panel(first, scenario), monkeypatch)
    same_run(fused, general)
    assert fused.trace.events_of("error in the program")[0].t_ns == 12 * MS and fused.cpu.downloads == 1
    assert fused.trace.events_of("stick")[0].t_ns == 36 * MS  # TL held since the end of the step at 30 ms
    assert fused.cpu.read("M") == 40 - 30  # TL read TRUE from its press at 30 ms until the clear at 40 ms
    assert 12 * MS in steps and 14 * MS not in steps  # the scan that raised was fused; the CPU then in STOP
    assert {25 * MS, 35 * MS, 45 * MS} <= set(steps) and 37 * MS not in steps  # the new program; the stuck wire


@pytest.mark.parametrize(
    ("number", "scenario"),
    [
        ("4.3.5", "three objects"),  # parts removed by sensor triggers polled in every step
        ("4.3.6", None),  # every scenario: chatter faults on the wiring, in the middle of the run
        ("4.3.8", None),  # Clock_1Hz: the clock memory latched at its edges (by the general path)
        ("4.3.17", "six mixed"),  # an analog input
        ("4.3.20", None),  # a cyclic interrupt OB30: never fused
    ],
)
def test_a_shipped_solution_gives_the_same_trace_fused_or_not(number, scenario, monkeypatch):
    exercise = get(number)
    names = [scenario] if scenario is not None else [s.name for s in exercise.scenarios]
    shares = []
    for name in names:

        def build(name=name, **options: bool) -> Simulation:
            sim = exercise.simulation(exercise.reference.program(), exercise.scenario(name), seed=2, **options)
            sim.fast_forward = False
            return sim

        fused, general, steps = both_paths(build, monkeypatch)
        same_run(fused, general)
        shares.append(len(steps) / fused.cpu.scan_count)
    if number == "4.3.20":
        assert max(shares) == 0
    else:  # (a wire chattering from the start takes every step of its run to the general path)
        assert max(shares) > 0.9


@pytest.mark.parametrize(("number", "scenario"), [("4.3.5", "three objects"), ("4.3.6", "five objects")])
def test_polling_the_triggers_only_on_a_change_gives_the_trace_of_polling_every_step(number, scenario, monkeypatch):
    """The loop polls the scenario's sensor triggers only when a watched sensor changed or something is due; a
    getter that never reads the same (every step polls, as before that) must give the same run."""
    exercise = get(number)
    polls: list[int] = []
    poll = simulation_module.ActionRunner.poll

    def counted(self, t: int, sensors: dict) -> None:
        polls.append(t)
        poll(self, t, sensors)

    monkeypatch.setattr(simulation_module.ActionRunner, "poll", counted)

    def run() -> Simulation:
        sim = exercise.simulation(exercise.reference.program(), exercise.scenario(scenario), seed=3)
        sim.fast_forward = False
        sim.run()
        return sim

    watched = run()
    some = len(polls)
    monkeypatch.setattr(simulation_module, "itemgetter", lambda *names: lambda sensors: object())
    every = run()
    same_run(watched, every)
    assert 0 < 100 * some < len(polls) - some  # a few polls, at the changes and the triggers' times; the other
    # run polled in every step while a trigger could fire
