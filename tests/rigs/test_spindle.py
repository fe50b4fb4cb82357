"""SPINDLE: the contactors' pick-up and drop-out delays, the short circuit a hasty reversal makes, the
chapter's two faults, and the chapter's CWCCW (M-07) reversing the spindle on it in both forms."""

from __future__ import annotations

import pytest
from mech_examples import SPINDLE_TAGS, path

from plants import Spindle
from plcsim import CPU, Simulation
from plcsim.frontends import read_program
from plcsim.plant.check import check_plant
from plcsim.scenario.planning import Scenario
from plcsim.scenario.verbs import jam_motor, press, stuck, write
from plcsim.sim.wiring import NO


def test_the_rig_keeps_the_plant_protocol():
    assert check_plant(Spindle())["signals"] == 9


def test_a_contact_follows_its_coil_after_the_pick_up_and_drop_out_delays():
    s = Spindle()
    s.actuate("SMN", True)
    s.step(40_000_000)
    assert s.sensors["KSMN"] is True
    s.actuate("SMN", False)
    s.step(29_000_000)
    assert s.sensors["KSMN"] is True
    s.step(1_000_000)
    assert s.sensors["KSMN"] is False
    assert [(e.t_ns // 1_000_000, e.kind, e.subject) for e in s.events] == [
        (40, "contactor picked up", "SMN"),
        (70, "contactor dropped out", "SMN"),
    ]


def test_switching_the_other_contactor_on_before_the_first_has_dropped_out_is_a_short_circuit():
    s = Spindle(pick_up=0.010, drop_out=0.030)
    s.actuate("SMP", True)
    s.step(3_000_000_000)
    assert s.rpm == 1000.0 and s.quiescent()
    s.actuate("SMP", False)
    s.actuate("SMN", True)  # closes after 10 ms, SMP opens after 30 ms
    s.step(50_000_000)
    assert [e.kind for e in s.events][-3:] == ["contactor picked up", "short circuit", "contactor dropped out"]


def test_a_jammed_contactor_never_picks_up_and_picks_up_when_freed():
    s = Spindle()
    s.jam_motor("SMN", True)
    s.actuate("SMN", True)
    s.step(1_000_000_000)
    assert s.sensors["KSMN"] is False and s.rpm == 0.0
    s.jam_motor("SMN", False)
    s.step(40_000_000)
    assert s.sensors["KSMN"] is True


def _reversal(suffix: str, *faults) -> Simulation:
    """Spindle running CW (an HMI write switches SMP on at 0 s); START at 1 s runs CWCCW (M-07)."""
    cpu = CPU(tags=SPINDLE_TAGS, program=read_program(path("m07_cwccw_tex", suffix)))
    scenario = Scenario(
        "reverse", write("SMP", True, t="0ms"), *press("START", t="1s", hold="50ms"), *faults, duration="4s"
    )
    wires = [NO(name) for name in ("START", "KSMP", "KSMN", "SMP", "SMN")]
    sim = Simulation(cpu, Spindle(), wires, scenario)
    sim.run()
    return sim


@pytest.mark.parametrize("suffix", [".mech", ".py"])
def test_m07_reverses_the_spindle_without_a_short_circuit(suffix):
    sim = _reversal(suffix)
    kinds = [(e.t_ns // 1_000_000, e.kind, e.subject) for e in sim.trace.events if e.source == "plant"]
    contactor = [k for k in kinds if k[1].startswith("contactor")]
    # SMP off from the end of the scan at 1.001 s, its contact drops 30 ms later; the scan that sees it
    # (1.031 s) starts the TIM, which passes at 1.231 s; SMN is on from that scan's end and picks up 40 ms later
    assert contactor == [
        (41, "contactor picked up", "SMP"),
        (1031, "contactor dropped out", "SMP"),
        (1272, "contactor picked up", "SMN"),
    ]
    assert not [k for k in kinds if k[1] == "short circuit"]
    assert sim.cpu.read("CWCCW.ACTIVE") is False and sim.cpu.t.BZH11 == 0
    assert sim.plant.rpm < -990  # turning counter-clockwise


@pytest.mark.parametrize("suffix", [".mech", ".py"])
def test_m07_a_stuck_ksmp_is_error_4_04(suffix):
    sim = _reversal(suffix, stuck("KSMP", True, t="0ms"))
    assert sim.cpu.t.BZH11 == 4 and sim.cpu.t.SMN is False and sim.cpu.read("CWCCW.ACTIVE") is False


@pytest.mark.parametrize("suffix", [".mech", ".py"])
def test_m07_a_contactor_that_never_picks_up_is_error_4_05(suffix):
    sim = _reversal(suffix, jam_motor("SMN", t="0ms"))
    assert sim.cpu.t.BZH11 == 5 and sim.cpu.t.SMN is False
    assert sim.trace.falls("CWCCW.ACTIVE")[0] // 1_000_000 == 2231  # 1 s after the scan that switched SMN on


def test_both_forms_record_the_same_trace_on_the_rig():
    assert _reversal(".mech").trace.digest() == _reversal(".py").trace.digest()


def test_checks_read_the_step_its_time_and_the_error_from_the_trace():
    from plcsim.check import Context, becomes, falls, never, rises, value

    ctx = Context.of(_reversal(".mech", stuck("KSMP", True, t="0ms")).trace)
    assert becomes(value("CWCCW.ERR") == 4).within("1s + 2 scans").after(rises("CWCCW.ACTIVE")).evaluate(ctx).passed
    # the last scan it waits has ET 999 ms; the next reaches 1 s, jumps to CW_ERR and ends (ET back to 0)
    assert falls("CWCCW.ACTIVE").within("1 scan").after(becomes(value("CWCCW.ET") >= 999)).evaluate(ctx).passed
    assert never(value("CWCCW.STEP") > 1).evaluate(ctx).passed  # it never got past the TEX1
    ok = Context.of(_reversal(".py").trace)
    assert becomes(value("CWCCW.STEP") == 3).within("1s").after(rises("CWCCW.ACTIVE")).evaluate(ok).passed
    assert not never(value("CWCCW.STEP") > 1).evaluate(ok).passed
