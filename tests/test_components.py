"""The component protocol: a rig built from components, its declarations, faults and rig-supplied verbs."""

from __future__ import annotations

import pytest

from plants.components import Axis, LimitSwitch
from plants.conveyors import BarrierLayout, BeltLayout, ConveyorLine
from plcsim import CPU, Tag
from plcsim.check import action, count, event
from plcsim.errors import ExerciseError
from plcsim.plant import check_plant
from plcsim.scenario import RigVerb, Scenario, place
from plcsim.sim import Simulation
from plcsim.wiring import Wire

MS = 1_000_000


class PressLine(ConveyorLine):
    """A belt with a press ram on a kinematic axis (the shape of PUNCH), and one rig verb."""

    VERBS = {"jam_ram": RigVerb("jam_ram", "jam_ram", "axis", "jam the ram {target}", targets="axes")}

    def __init__(self) -> None:
        self.ram = Axis(
            "RAM",
            0.0,
            39.0,
            start=3.0,
            speed=25.0,
            plus="DOLE",
            minus="HORE",
            cams=[LimitSwitch("KS1", 2.0, 4.0), LimitSwitch("KS2", 35.0, 37.0)],
            drawing=(215.0, 105.0, 0.0, -1.0, 20.0, 30.0),
        )
        self.axes = {"RAM": self.ram}
        super().__init__(
            "PRESSLINE", [BeltLayout("M1", "M1", 280.0)], [BarrierLayout("OS1", "M1", 45.0)], components=[self.ram]
        )

    def jam_ram(self, target: str) -> None:
        self.jam_motor(target, True)


def test_a_rig_with_a_component_keeps_the_protocol():
    plant = PressLine()
    summary = check_plant(plant)
    assert {"DOLE", "HORE", "KS1", "KS2"} <= set(plant.signals)
    assert {"axis stalled", "interlock violated", "motor jammed"} <= plant.EVENTS
    assert "RAM" in plant.event_subjects()
    assert summary["drawables"] > 0


def test_the_axis_moves_while_the_belt_idles_and_stalls_at_its_end_stop():
    plant = PressLine()
    assert plant.quiescent()
    plant.actuate("DOLE", True)
    assert not plant.quiescent()
    while not plant.sensors["KS2"]:
        plant.step(MS)
    assert plant.now_ns == 1281 * MS and not plant.sensors["KS1"]  # 32 mm at 25 mm/s
    for _ in range(200):
        plant.step(MS)
    assert [(e.kind, e.subject, e.data["end"]) for e in plant.events] == [("axis stalled", "RAM", "hi")]
    plant.actuate("DOLE", False)
    plant.step(MS)
    assert plant.quiescent()  # settled: the idle steps can be skipped


def test_a_shifted_cam_is_seen_at_once():
    plant = PressLine()
    assert plant.sensors["KS1"]
    plant.shift_sensor("KS1", 5.0)
    plant.step(MS)
    assert not plant.sensors["KS1"]


def run(scenario: Scenario) -> Simulation:
    tags = {"OS1": Tag("%I0.0"), "KS2": Tag("%I0.1"), "DOLE": Tag("%Q0.0"), "M1": Tag("%Q0.1")}
    cpu = CPU(tags, "def OB1(t):\n    t.DOLE = not t.KS2\n")
    wires = [Wire("OS1", "OS1"), Wire("KS2", "KS2"), Wire("DOLE", "DOLE"), Wire("M1", "M1")]
    sim = Simulation(cpu, PressLine(), wires, scenario)
    sim.run()
    return sim


def test_a_rig_verb_needs_no_edit_in_plcsim():
    jam_ram = PressLine.VERBS["jam_ram"]
    sim = run(Scenario("jam", place("p1", at="OS1", t="10ms"), jam_ram("RAM", t="500ms"), duration="2s"))
    tr = sim.trace
    assert [(e.kind, e.subject) for e in tr.events_of(source="scenario")] == [("place", "p1"), ("jam_ram", "RAM")]
    assert [e.kind for e in tr.events_of("motor jammed")] == ["motor jammed"]
    assert not tr.column("KS2").any()  # jammed half-way down: KS2 is never reached
    from plcsim.check import evaluate_all

    verdicts = evaluate_all([count(action("jam_ram")).equals(1), count(event("motor jammed", "RAM")).equals(1)], tr)
    assert all(v.passed for _, v in verdicts), verdicts


def test_a_rig_verb_with_a_bad_target_or_on_a_rig_without_it_is_refused_before_the_run():
    jam_ram = PressLine.VERBS["jam_ram"]
    with pytest.raises(ExerciseError, match=r"jam the ram RAMM at 1 s: no axis 'RAMM'; did you mean 'RAM'\?"):
        run(Scenario("bad", jam_ram("RAMM", t="1s"), duration="2s"))
    other = RigVerb("jam_piston", "jam_piston", "piston", "jam piston {target}", targets="pistons")
    with pytest.raises(ExerciseError, match=r"the rig has no verb 'jam_piston'.*its verbs: jam_ram"):
        run(Scenario("bad", other("P1", t="1s"), duration="2s"))
