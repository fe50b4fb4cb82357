"""Issue 11, first steps: observers as lists, tasks numbered by their spec, the period default, pacing."""

from __future__ import annotations

import subprocess
import sys
import time

import pytest

from plants import Panel
from plcsim import CPU, CPUConfig, Int, Program, Simulation, Tag
from plcsim.check.base import Context
from plcsim.check.occurrences import calls
from plcsim.sim.simulation import Realtime, RealtimeSimulation
from plcsim.sim.wiring import NO
from plcsim.trace.facade import Trace

TAGS = {"TL": Tag("%I0.0"), "LED": Tag("%Q0.0"), "N": Tag("%MW10", Int)}
BLINK = """
def OB1(t):
    t.LED = t.TL

def tick(t):
    t.N = t.N + 1

OB30 = CyclicInterrupt(tick{period})
"""


def panel_sim(program: str = BLINK.format(period=', period="10ms"'), **kw) -> Simulation:
    cpu = CPU(tags=TAGS, program=program, **kw.pop("cpu_options", {}))
    return Simulation(cpu, Panel(buttons=("TL",), switches=(), lamps=("LED",)), [NO("TL"), NO("LED")], **kw)


def test_a_live_panel_and_the_recorder_both_see_every_scan_and_the_trace_is_unchanged():
    alone = panel_sim()
    alone.run("50ms")
    sim = panel_sim()
    panel_scans, panel_tasks = [], []
    sim.cpu.scan_end.add(lambda cpu: panel_scans.append(cpu.scan_end_ns))
    sim.cpu.task_end.add(lambda cpu, task, start, end: panel_tasks.append((task, start)))
    sim.cpu.on_scan_end = lambda cpu: None  # an assigned hook replaces only itself, never the recorder
    sim.run("50ms")
    assert sim.trace.digest() == alone.trace.digest()
    assert len(panel_scans) == len(sim.trace.rows_of("OB1")) == 50 - len(panel_tasks)
    assert panel_tasks[:3] == [("OB30", 0), ("OB30", 10_000_000), ("OB30", 20_000_000)]


def test_a_detached_recorder_stops_writing_and_the_other_subscribers_stay():
    sim = panel_sim()
    seen = []
    sim.cpu.scan_end.add(seen.append)
    sim.run("10ms")
    rows = len(sim.trace)
    sim.recorder.detach()
    sim.run("10ms")
    # each 10 ms holds one 1 ms OB30 call (at 0 and at 10 ms) and 9 scans of 1 ms
    assert rows == 1 + 9 and len(sim.trace) == rows and len(seen) == 9 + 9


def test_the_trace_keeps_the_task_numbers_its_cpu_declared_and_calls_reads_them(tmp_path):
    sim = panel_sim()
    sim.run("30ms")
    assert sim.trace.task_numbers == {"OB1": 1, "OB30": 30}
    again = Trace.load(sim.trace.save(tmp_path / "run.npz"))
    assert again.task_numbers == {"OB1": 1, "OB30": 30}
    assert calls("OB30").times(Context.of(again)).tolist() == [0, 10_000_000, 20_000_000]


def test_calls_of_a_task_that_is_not_an_ob_reads_the_trace_s_task_names():
    tr = Trace(["M"], types={"M": "bool"}, task_numbers={"P12": 12})
    for k, task in enumerate([1, 12, 1, 12]):
        tr.add_row(k * 1_000_000, (k + 1) * 1_000_000, task, (False,))
    assert calls("P12").times(Context.of(tr)).tolist() == [1_000_000, 3_000_000]
    with pytest.raises(ValueError, match="no task named 'P13'"):
        calls("P13").times(Context.of(tr))


@pytest.mark.parametrize(
    ("given", "configured", "expected_ms"),
    [("", {}, 100), ("", {"OB30": "20ms"}, 20), (', period="5ms"', {"OB30": "20ms"}, 5)],
)
def test_the_interrupt_period_is_the_program_s_else_the_configuration_s_else_100ms(given, configured, expected_ms):
    program = Program.from_source(BLINK.format(period=given))
    spec = program.tasks["OB30"]
    assert spec.period_ns == (None if not given else 5_000_000)
    cpu = CPU(tags=TAGS, program=program, config=CPUConfig(periods=configured))
    cpu.run("201ms")
    calls_in_201ms = 201 // expected_ms + 1
    assert calls_in_201ms == cpu.t.N
    assert program.tasks["OB30"] is spec and spec.period_ns == (None if not given else 5_000_000)  # not mutated


def test_pacing_is_chosen_when_the_simulation_is_built_and_changes_nothing_but_the_wall_time():
    fast = panel_sim()
    fast.run("100ms")
    paced = panel_sim(pacing=Realtime(2.0))
    wall = time.perf_counter()
    paced.run("100ms")
    assert time.perf_counter() - wall >= 0.05 * 0.95
    assert paced.trace.digest() == fast.trace.digest()
    assert RealtimeSimulation(CPU(tags=TAGS, program="def OB1(t):\n    pass\n"), factor=3.0).factor == 3.0


def test_the_trace_core_imports_none_of_its_exporters():
    exporters = "('plcsim.trace.plot', 'plcsim.trace.rerun')"
    code = f"import sys, plcsim.trace.facade; print(sorted(m for m in sys.modules if m in {exporters}))"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert out.strip() == "[]"
