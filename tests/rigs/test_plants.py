"""The plant models against the protocol, and their components (panel, machine, belt drive, limit switch)."""

from __future__ import annotations

import math

import numpy as np
import pytest

from plants import RIGS, Conv1, Machine, Panel
from plants.components import Belt, Bench, LimitSwitch, OperatorPanel, WorkpieceSpec
from plcsim.plant.check import check_plant
from plcsim.plant.protocol import PARTS, Plant, PlantEvent, capable

MS = 1_000_000


@pytest.mark.parametrize("rig", sorted(RIGS), ids=sorted(RIGS))
def test_every_rig_keeps_the_protocol(rig):
    plant = RIGS[rig]()
    assert isinstance(plant, Plant)
    summary = check_plant(plant)
    assert summary["signals"] == len(plant.signals) > 0
    assert summary["drawables"] > 0
    assert plant.now_ns == 0 and plant.events == []  # check_plant leaves the plant reset


def test_check_plant_reports_a_broken_plant():
    class Drifting(Conv1):
        def step(self, dt_ns):
            super().step(dt_ns)
            self.now_ns += 1  # one ns too many

    with pytest.raises(AssertionError, match=r"moved now_ns from 0 to 1000001"):
        check_plant(Drifting())


def test_check_plant_catches_nondeterminism():
    class Noisy(Conv1):
        runs = 0

        def reset(self, *, seed=None):
            super().reset(seed=seed)
            Noisy.runs += 1
            self.sensors["S1"] = Noisy.runs % 2 == 0  # differs from run to run

    with pytest.raises(AssertionError, match="two runs with seed 1234 differ"):
        check_plant(Noisy())


def test_signal_names_match_the_textbook_io_tables():
    def split(p):
        sensors = [k for k, s in p.signals.items() if s.direction == "sensor"]
        actuators = [k for k, s in p.signals.items() if s.direction == "actuator"]
        return sensors, actuators

    assert split(RIGS["CONV1"]()) == (["S1", "S2"], ["D1"])
    assert split(RIGS["CONV3"]()) == (["D1_OS", "D2_OS", "D3_OS"], ["D1_VPRED", "D2_VPRED", "D3_VPRED"])
    assert split(RIGS["CONV2x2"]()) == (["D1_OS1", "D1_OS2", "D2_OS1", "D2_OS2"], ["D1_VPRED", "D2_VPRED"])
    assert split(RIGS["MACHINE"]()) == ([], ["STROJ_ZAP"])
    panel = RIGS["PANEL"]()
    assert split(panel) == (["TLACIDLO", "TL", "TLACIDLO_ZAP", "TLACIDLO_VYP", "PREPINAC"], ["LED"])
    assert all(panel.signals[k].operator for k in split(panel)[0])
    assert list(RIGS["CONV1"]().stations) == ["S1", "S2", "belt"]
    assert list(RIGS["CONV3"]().stations) == ["D1_OS", "D2_OS", "D3_OS", "D1", "D2", "D3"]
    assert [s.x for s in RIGS["CONV2x2"]().stations.values()] == [40.0, 265.0, 345.0, 570.0, 0.0, 305.0]
    led = Conv1(lamps=("LED",))
    assert led.signals["LED"].direction == "actuator"


def test_panel_buttons_switches_and_lamps():
    p = Panel(buttons=("TL",), switches=("PREPINAC",), lamps=("LED", "H1"))
    live = p.sensors
    p.operate("TL", True)
    p.step(MS)
    p.operate("TL", True)  # no change, no event
    p.operate("PREPINAC", 1)
    p.step(2 * MS)
    p.operate("TL", False)
    p.actuate("LED", True)
    assert p.sensors is live and p.sensors == {"TL": False, "PREPINAC": True}
    assert [(e.t_ns, e.kind, e.subject) for e in p.events] == [
        (0, "button pressed", "TL"),
        (1 * MS, "button pressed", "PREPINAC"),
        (3 * MS, "button released", "TL"),
    ]
    assert p.events[1].data == {"control": "switch"}
    assert p.lamps == {"LED": True, "H1": False}
    dyn = {d.path: d for d in p.dynamic_drawables()}
    assert dyn["panel/lamps/LED"].color == (255, 200, 30) and dyn["panel/lamps/H1"].color == (70, 70, 70)
    with pytest.raises(ValueError, match="LED is a lamp"):
        p.operate("LED", True)
    with pytest.raises(KeyError, match="no button or switch 'XX'"):
        p.operate("XX", True)
    assert not capable(p, PARTS) and not hasattr(p, "place")  # a panel handles no parts: it declares so, no stub
    p.reset()
    assert p.sensors is live and p.sensors == {"TL": False, "PREPINAC": False} and p.now_ns == 0
    assert p.lamps == {"LED": False, "H1": False}


def test_operator_panel_rejects_duplicates():
    with pytest.raises(ValueError, match=r"duplicate names \['A'\]"):
        OperatorPanel(buttons=("A",), lamps=("A",))


def test_machine_accumulates_on_time():
    m = Machine()
    for _ in range(3):  # 4.3.13: three cycles of 1 s on, 2 s off
        m.actuate("STROJ_ZAP", True)
        for _ in range(1000):
            m.step(MS)
        m.actuate("STROJ_ZAP", False)
        for _ in range(2000):
            m.step(MS)
    assert m.on_time_ns == 3_000_000_000 and m.on_time_s == 3.0
    assert m.starts == 3 and m.now_ns == 9_000_000_000
    assert m.observables() == {"on_time_s": 3.0, "starts": 3.0}
    m.actuate("STROJ_ZAP", True)
    m.actuate("STROJ_ZAP", True)  # already on: not a new start
    assert m.starts == 4
    with pytest.raises(KeyError, match="no actuator 'D1'"):
        m.actuate("D1", True)


def test_belt_drive_is_first_order():
    b = Belt("D1", 0.0, 330.0, 40.0, speed=50.0, tau_s=0.05)
    assert b.command(1) is True
    v = []
    for _ in range(50):  # 50 ms = one time constant
        b.drive(0.001)
        v.append(b.v)
    assert v[-1] == pytest.approx(50.0 * (1 - math.exp(-1.0)), rel=1e-9)
    while b.drive(0.001):
        pass
    assert b.v == 50.0
    host = Bench()
    assert b.jam(host, True) is True and b.target == 0.0
    assert [(e.kind, e.subject) for e in host.events] == [("motor jammed", "D1")]
    b.jam(host, False)
    assert b.target == 50.0
    with pytest.raises(ValueError, match="forward only"):
        b.command(-1)
    rev = Belt("M1", 0.0, 280.0, 50.0, speed=40.0, reversible=True)
    rev.command(-1)
    assert rev.target == -40.0


def test_limit_switch_zone_and_hysteresis():
    sw = LimitSwitch("KS1", 100.0, 102.0)  # 2 mm zone, 0.5 mm hysteresis
    trace = [(x, sw.update(x), sw.actuated) for x in (99.0, 99.9, 100.0, 99.6, 99.4, 101.0, 102.4, 102.6)]
    assert [a for _, _, a in trace] == [False, False, True, True, False, True, True, False]
    sw.shift(5.0)
    assert sw.update(101.0) is False and sw.actuated is False
    assert sw.update(105.5) is True and sw.actuated is True


def test_workpiece_rest_height():
    spec = WorkpieceSpec()
    assert (spec.length, spec.depth, spec.height, spec.mass_g) == (30.0, 30.0, 20.0, 12.0)
    assert spec.rest_height(0.0) == 10.0
    assert spec.rest_height(math.radians(90)) == pytest.approx(15.0)


def test_drawables_show_state():
    c = Conv1(end="stop", lamps=("LED",))
    c.place("S1", color=(10, 20, 30))
    c.step(MS)
    c.actuate("LED", True)
    c.actuate("D1", True)
    c.step(MS)
    dyn = {d.path: d for d in c.dynamic_drawables()}
    part = dyn["parts/p1"]
    assert part.kind == "polygon" and part.text == "p1" and part.color == (10, 20, 30)
    assert part.points.shape == (4, 2)
    np.testing.assert_allclose(part.points.mean(axis=0), [40.0, 50.0], atol=0.1)
    assert dyn["beams/S1"].color == (230, 40, 40) and dyn["beams/S2"].color == (60, 190, 60)
    assert dyn["panel/lamps/LED"].color == (255, 60, 40)
    assert "belt/D1/direction" in dyn
    static = {d.path for d in c.static_drawables()}
    assert {"belt/D1", "frame/end_stop", "sensors/S1", "sensors/S2", "sensors/S1/label"} <= static
    x0, y0, x1, y1 = c.bounds()
    assert x0 < 0.0 and x1 > 335.0 and y0 < 0.0 and y1 > 60.0


def test_events_are_plant_events_with_plant_time():
    c = Conv1()
    c.place("S1")
    for _ in range(5):
        c.step(MS)
    assert all(isinstance(e, PlantEvent) and isinstance(e.t_ns, int) for e in c.events)
    assert [(e.t_ns, e.kind, e.subject, e.part) for e in c.events] == [
        (0, "part placed", "S1", "p1"),
        (1 * MS, "part entered", "S1", "p1"),
    ]
