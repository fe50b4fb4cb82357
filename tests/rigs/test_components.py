"""The component protocol: a rig built from components, its declarations, faults and rig-supplied verbs."""

from __future__ import annotations

import pytest

from plants import RIGS
from plants.components import Axis, Belt, EndStop, LightBarrier, LimitSwitch, OperatorPanel, SideViewPlant
from plants.conveyors import BarrierLayout, BeltLayout, ConveyorLine
from plcsim import CPU, Tag
from plcsim.check import action, count, event
from plcsim.core.errors import ExerciseError
from plcsim.plant.check import check_plant
from plcsim.plant.protocol import OPERATOR, Station
from plcsim.plant.verbs import RigVerb
from plcsim.scenario.planning import Scenario
from plcsim.scenario.verbs import place
from plcsim.sim.simulation import Simulation
from plcsim.sim.wiring import Wire

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


def test_the_colour_sensor_reads_the_part_over_its_spot_with_noise_and_ambient_light():
    from plants.components.colour_sensor import ColourSensor
    from plants.components.top_view import TopViewPlant
    from plants.components.workpiece import WorkpieceSpec
    from plcsim.plant.protocol import Station

    sensor = ColourSensor("FARBA", 0.0, 0.0, colours={1: 5000, 2: 13000, 3: 21000}, noise=500.0)
    plant = TopViewPlant(
        "COLOUR",
        components=[sensor],
        stations=[Station("spot", 0.0, 0.0)],
        table=(-50.0, -50.0, 50.0, 50.0),
        workpiece=WorkpieceSpec(length=25.0, depth=25.0, mass_g=10.0),
    )
    assert plant.signals["FARBA"].kind == "analog" and plant.sensors["FARBA"] == 26500  # the bare belt
    plant.place("spot", part="red", colour=2)
    readings = []
    for _ in range(2000):
        plant.step(MS)
        readings.append(plant.sensors["FARBA"])  # readings[i] at (i + 1) ms
    # a new value once per 5 ms conversion cycle, held in between: the first conversion (5 ms) sees the part
    assert readings[:4] == [26500] * 4 and readings[4] != 26500
    assert all((i + 1) % 5 == 0 for i in range(1, 2000) if readings[i] != readings[i - 1])
    conversions = readings[4::5]
    mean, spread = sum(conversions) / 400, max(conversions) - min(conversions)
    assert abs(mean - 13000) < 100 and 500 < spread < 8 * 500  # σ 500: the spread of 400 draws is ≈ 6 σ
    sensor.set_ambient(plant, 1500.0)
    held = plant.sensors["FARBA"]
    for _ in range(4):
        plant.step(MS)
        assert plant.sensors["FARBA"] == held  # 2001 .. 2004 ms: the conversion of 2000 ms holds
    plant.step(MS)
    assert abs(plant.sensors["FARBA"] - 14500) < 2500
    plant.remove("red")
    for _ in range(5):
        plant.step(MS)
    assert plant.sensors["FARBA"] == 27648  # 26500 + 1500, clipped to the module's range


def test_a_piston_moves_out_only_once_the_compressor_has_built_30_percent():
    from plants.components.compressor import Compressor
    from plants.components.piston import Piston
    from plants.components.top_view import TopViewPlant
    from plants.components.workpiece import WorkpieceSpec

    air = Compressor("K", "Kompresor")
    piston = Piston("P1", "Piest1", origin=(0.0, 0.0), direction=(0.0, 1.0), stroke=70.0, supply=air.fraction)
    plant = TopViewPlant(
        "PNEU", components=[air, piston], stations=[], table=(-50, -20, 50, 100), workpiece=WorkpieceSpec()
    )
    plant.actuate("Piest1", True)
    for _ in range(500):
        plant.step(MS)
    assert piston.s < 0.01  # the valve is open, but there is no air
    plant.actuate("Kompresor", True)
    t0 = plant.now_ns
    while piston.s < 1.0 and plant.now_ns - t0 < 1000 * MS:
        plant.step(MS)
    # p = 1 - exp(-t/0.1 s) passes 0.3 after 36 ms; the plate then covers 1 mm at 80 mm/s in ≈ 13 ms
    assert 45 * MS <= plant.now_ns - t0 <= 55 * MS
    while not [e for e in plant.events if e.kind == "piston extended"]:
        plant.step(MS)
    assert plant.now_ns - t0 < 1000 * MS


def test_a_plant_that_declares_nothing_is_refused_with_the_reason():
    from types import SimpleNamespace

    from plcsim.core.errors import ConfigurationError
    from plcsim.scenario.names import plant_vocabulary

    old = SimpleNamespace(name="OLD", VERBS={}, event_subjects=set)  # a plant of the old protocol
    with pytest.raises(ConfigurationError, match=r"'OLD' does not declare \['EVENTS', 'CAPABILITIES'\]"):
        plant_vocabulary(old)


# --- the side-view rigs as assemblies ----------------------------------------------------------------------------


def shuttle_rig(*extra) -> SideViewPlant:
    """A reversible belt with two beams, made of components only (the shape of PUNCH's belt)."""
    belt = Belt("M1", 0.0, 280.0, 50.0, speed=40.0, forward="FWD", backward="BACK")
    beams = [LightBarrier("OS1", 45.0, 60.0), LightBarrier("OS2", 230.0, 60.0)]
    stations = [Station("OS1", 45.0, 50.0), Station("OS2", 230.0, 50.0)]
    return SideViewPlant("SHUTTLE", components=[*beams, belt, *extra], stations=stations)


def test_a_side_view_rig_is_the_sum_of_its_components():
    plain = shuttle_rig()
    assert list(plain.signals) == ["OS1", "OS2", "FWD", "BACK"]
    assert {"part entered", "interlock violated", "motor jammed"} <= plain.EVENTS
    assert "end stop hit" not in plain.EVENTS and "button pressed" not in plain.EVENTS
    assert OPERATOR not in plain.CAPABILITIES
    assert plain.event_subjects() == {"OS1", "OS2", "M1", "FWD", "BACK"}
    fitted = shuttle_rig(EndStop("stop", 280.0, 50.0), OperatorPanel(buttons=("START",), origin=(320.0, 0.0)))
    assert {"end stop hit", "button pressed"} <= fitted.EVENTS and OPERATOR in fitted.CAPABILITIES
    assert check_plant(fitted)["signals"] == 5
    paths = [d.path for d in fitted.static_drawables()]
    assert paths.index("belt/M1") < paths.index("frame/stop") < paths.index("sensors/OS1") < paths.index("panel/plate")
    assert "end stop hit" not in RIGS["CONV1"]().EVENTS and "end stop hit" in RIGS["CONV1"](end="stop").EVENTS


def run_shuttle(program: str, seconds: str = "300ms") -> Simulation:
    tags = {"OS1": Tag("%I0.0"), "FWD": Tag("%Q0.0"), "BACK": Tag("%Q0.1")}
    wires = [Wire("OS1", "OS1"), Wire("FWD", "FWD"), Wire("BACK", "BACK")]
    sim = Simulation(
        CPU(tags, program), shuttle_rig(), wires, Scenario("run", place("p1", at="OS1", t="0s"), duration=seconds)
    )
    sim.run()
    return sim


def test_a_reversal_across_one_scan_boundary_is_no_interlock_violation():
    """The belt reverses in every scan: FWD and BACK are never TRUE in the same scan, but one of them is written
    first when the outputs reach the plant (FWD on while BACK is still on, every second scan). The relays are
    taken together at the next step, so nothing is reported (6.3: only both TRUE is the relay H-bridge's short)."""
    sim = run_shuttle("def OB1(t):\n    t.FWD = not t.FWD\n    t.BACK = not t.FWD\n")
    tr = sim.trace
    assert not (tr.column("FWD") & tr.column("BACK")).any() and tr.column("FWD").sum() == 150
    assert tr.events_of("interlock violated") == []


def test_both_relays_on_in_one_scan_stop_the_belt_and_are_reported_once():
    sim = run_shuttle("def OB1(t):\n    t.FWD = True\n    t.BACK = t.FWD\n")
    (e,) = sim.trace.events_of("interlock violated")
    assert (e.subject, e.data["reason"], e.t_ns) == ("M1", "both directions commanded", 1_000_000)
    assert sim.plant.belt_speeds() == {"M1": 0.0}


class _Stepper:
    """A component busy for ``steps`` advances; on its ``at``-th advance it wakes ``other`` (a part reached it)."""

    EVENTS: frozenset[str] = frozenset()

    def __init__(self, name: str, steps: int, other: _Stepper | None = None, at: int = 0) -> None:
        self.name, self.steps, self.other, self.at = name, steps, other, at
        self.advanced: list[int] = []

    def specs(self) -> list:
        return []

    def subjects(self) -> set[str]:
        return set()

    def reset(self, host) -> bool:
        return self.steps > 0

    def actuate(self, host, signal, value) -> bool:
        return False

    def advance(self, host, dt: float) -> bool:
        self.advanced.append(host.now_ns // MS)
        if self.other is not None and len(self.advanced) == self.at:
            self.other.steps = 1
            host.wake(self.other)
        return len(self.advanced) < self.steps

    def static_drawables(self) -> list:
        return []

    def dynamic_drawables(self) -> list:
        return []


def _run(components: list[_Stepper], steps: int) -> None:
    """Advance an assembly of ``components`` ``steps`` times on a bench whose ``wake`` is the assembly's."""
    from plants.components.component import Assembly, Bench

    assembly = Assembly(components)
    host = Bench()
    host.wake = assembly.wake
    assembly.reset(host)
    for _ in range(steps):
        host.now_ns += MS
        assembly.advance(host, 1e-3)


@pytest.mark.parametrize("steps_a", [1, 5], ids=["waker settles", "waker stays busy"])
def test_a_component_woken_during_the_only_busy_ones_step_advances_in_the_next(steps_a):
    woken = _Stepper("B", 0)
    _run([_Stepper("A", steps_a, woken, at=1), woken], 4)
    assert woken.advanced == [2]


def test_a_component_woken_during_a_step_of_several_advances_in_the_next():
    woken = _Stepper("B", 0)
    _run([_Stepper("A", 3, woken, at=2), _Stepper("C", 5), woken], 5)
    assert woken.advanced == [3]


def test_a_component_woken_after_it_settled_in_the_same_step_advances_again_in_the_next():
    first = _Stepper("B", 1)  # settles in its first advance, then C (after it in the list) wakes it in that step
    _run([first, _Stepper("C", 3, first, at=1)], 4)
    assert first.advanced == [1, 2]


def _shadowed(cams: list[LimitSwitch]) -> list[LimitSwitch]:
    """Copies of ``cams`` (same zones, same shift), to be read at every step."""
    out = []
    for c in cams:
        twin = LimitSwitch(c.name, c.lo, c.hi, hysteresis=c.hysteresis)
        twin.shift(c.dx)
        out.append(twin)
    return out


@pytest.mark.parametrize("kind", ["axis", "winch"])
def test_cams_read_only_outside_their_quiet_range_switch_as_cams_read_every_step(kind):
    """A carriage reads its cams only when it leaves the range where none can change (quiet_range): the sensors
    must be, step by step, those of the same cams read at every step: overlapping zones, a hysteresis, a reversal
    and a cam shifted mid-run."""
    from plants.components.component import Bench
    from plants.components.winch import Winch

    cams = [LimitSwitch("A", 10.0, 12.0), LimitSwitch("B", 30.0, 34.0, hysteresis=1.0), LimitSwitch("C", 33.0, 40.0)]
    if kind == "axis":
        carriage = Axis("X", 0.0, 50.0, start=1.0, speed=20.0, tau_s=0.02, plus="UP", minus="DOWN", cams=cams)
        drive = [("UP", True)], [("UP", False), ("DOWN", True)]
    else:
        carriage = Winch("X", -5.0, 50.0, start=1.0, v_fast=20.0, v_slow=10.0, cams=cams)
        drive = [("UP", True), ("FAST", True)], [("UP", False), ("DOWN", True), ("FAST", False), ("SLOW", True)]
    host = Bench()
    carriage.reset(host)
    shadow = _shadowed(cams)
    for sw in shadow:
        sw.update(carriage.s)
    changes = 0
    for k in range(6000):
        if k in (0, 2600):  # up, then down from near the top end
            for signal, value in drive[k > 0]:
                carriage.actuate(host, signal, value)
        if k == 1200:
            carriage.shift_cam("B", -3.0)
            shadow[1].shift(-3.0)
        host.step(carriage)
        changes += sum(sw.update(carriage.s) for sw in shadow)
        assert host.sensors == {sw.name: sw.actuated for sw in shadow}, f"step {k}, s = {carriage.s}"
    assert changes >= 8  # every cam made and broke on the way up and down
