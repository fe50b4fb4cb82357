"""Online monitoring: the power flow drawn is the RLO at each point for the CPU's state, and watching
changes nothing in the CPU (timers are read as last computed)."""

from __future__ import annotations

from exercises import get
from plcsim import CPU
from plcsim.ladder.monitor import PowerFlow
from plcsim.ladder.svg import NO_POWER, POWER
from plcsim.ladder.view import Ladder


def _running_belt():
    exercise = get("4.3.7")
    program = exercise.reference.program()
    cpu = CPU(exercise.tag_table(), program)
    cpu.set_input("S1", True)
    cpu.scan(3)
    cpu.set_input("S1", False)
    cpu.run("2s")
    return Ladder(program, exercise.tag_table()), cpu


def test_power_flows_through_the_timer_rung_while_the_belt_runs_and_stops_at_open_contacts():
    ladder, cpu = _running_belt()
    networks = ladder.networks()
    flow = PowerFlow(networks, cpu.t, ladder.program.constants)
    start, watchdog, stop, _ = networks
    s1, set_d1 = start.rungs[0].series.items
    assert flow(s1) == (True, False) and flow(set_d1) == (False, False)
    d1, not_s2, ton, alarm = watchdog.rungs[0].series.items
    assert flow(d1) == (True, True) and flow(not_s2) == (True, True)
    assert flow(ton) == (True, False) and flow(alarm) == (False, False)  # 2 s of 10: Q not yet
    assert flow.value('"TON_A"', "ET") == "T#2.002s"
    parallel, _ = stop.rungs[0].series.items
    assert flow(parallel) == (True, False)


def test_the_monitored_picture_colours_paths_and_watching_leaves_the_cpu_as_it_was():
    ladder, cpu = _running_belt()
    before = _as_last_computed(cpu)
    svg = ladder.monitor(cpu.t)
    assert POWER in svg and NO_POWER in svg and 'stroke-dasharray="5,3"' in svg
    assert "T#2.002s" in svg
    assert _as_last_computed(cpu) == before


def _as_last_computed(cpu):
    """The tags and the timer's members as a watch table reads them (never refreshing a timer)."""
    plain = {k: v for k, v in cpu.t.__dict__.items() if isinstance(v, bool | int | float)}
    return plain, [cpu.read(f"TON_A.{m}") for m in ("Q", "ET", "IN", "PT")]
