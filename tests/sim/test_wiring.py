"""Wiring (plcsim.sim.wiring): NO/NC contacts, analog scaling and noise, the faults (stuck-at, wire break,
chatter) and every validation error, which is raised before a run starts and names the fix.
"""

from __future__ import annotations

import statistics

import pytest

from plants import Conv1, Panel
from plcsim import CPU, Int, Simulation, Tag
from plcsim.plant.protocol import SignalSpec
from plcsim.scenario.planning import Scenario
from plcsim.scenario.verbs import chatter, clear, place, press, stuck, wire_break
from plcsim.sim.wiring import NC, NO, Wire, Wiring, WiringError, analog

MS = 1_000_000
IDLE = "def OB1(t):\n    pass\n"


class Tank:
    """A plant with analog signals: LEVEL 0..1000 mm (sensor), VALVE 0..100 % (actuator), FULL, PUMP."""

    name = "TANK"
    view = "side"
    EVENTS: frozenset = frozenset()
    CAPABILITIES: frozenset = frozenset()
    VERBS: dict = {}

    def __init__(self, level: float = 250.0):
        self.level = level
        self.signals = {
            "LEVEL": SignalSpec("LEVEL", "sensor", "analog", unit="mm", lo=0.0, hi=1000.0),
            "FULL": SignalSpec("FULL", "sensor"),
            "VALVE": SignalSpec("VALVE", "actuator", "analog", unit="%", lo=0.0, hi=100.0),
            "PUMP": SignalSpec("PUMP", "actuator"),
        }
        self.sensors: dict = {}
        self.events: list = []
        self.actuated: list = []
        self.reset()

    def reset(self, *, seed=None):
        self.now_ns = 0
        self.sensors.update({"LEVEL": self.level, "FULL": False})
        self.events.clear()
        self.actuated = []

    def actuate(self, name, value):
        self.actuated.append((self.now_ns, name, value))

    def step(self, dt_ns):
        self.now_ns += dt_ns

    def static_drawables(self):
        return []

    def dynamic_drawables(self):
        return []

    def event_subjects(self):
        return set()

    def bounds(self):
        return (0.0, 0.0, 1.0, 1.0)


TANK_TAGS = {"LEVEL": Tag("%IW64", Int), "FULL": Tag("%I0.0"), "VALVE": Tag("%QW64", Int), "PUMP": Tag("%Q0.0")}
TANK_PROGRAM = "def OB1(t):\n    t.VALVE = 13824\n    t.PUMP = t.FULL\n"


def tank_sim(level_wire: Wire | None = None, scenario=None, seed: int = 0, level: float = 250.0) -> Simulation:
    cpu = CPU(TANK_TAGS, TANK_PROGRAM)
    wires = [level_wire or analog("LEVEL"), NO("FULL"), analog("VALVE"), NO("PUMP")]
    return Simulation(cpu, Tank(level), wires, scenario, seed=seed)


def conveyor_sim(s1: Wire, s2: Wire, *actions, program: str = IDLE, seed: int = 0) -> Simulation:
    cpu = CPU({"S1": Tag("%I0.0"), "S2": Tag("%I0.1"), "D1": Tag("%Q0.0")}, program)
    scenario = Scenario("wiring", *actions, duration="100ms")
    return Simulation(cpu, Conv1(), [s1, s2, NO("D1")], scenario, seed=seed)


def panel_sim(*actions, seed: int = 0) -> Simulation:
    cpu = CPU({"TL": Tag("%I0.0"), "LED": Tag("%Q0.0")}, "def OB1(t):\n    t.LED = t.TL\n")
    plant = Panel(buttons=("TL",), switches=(), lamps=("LED",))
    return Simulation(cpu, plant, [NO("TL"), NO("LED")], Scenario("chatter", *actions, duration="400ms"), seed=seed)


# -- contacts --------------------------------------------------------------------------------------


def test_no_and_nc_levels():
    assert (NO("S1").level(True), NO("S1").level(False)) == (True, False)
    assert (NC("S1").level(True), NC("S1").level(False)) == (False, True)
    assert NC("S1") == Wire("S1", "S1", "NC")
    assert NO("S1", "START") == Wire("S1", "START", "NO")


def test_nc_barrier_reads_true_while_free_and_false_with_an_object():
    sim = conveyor_sim(NC("S1"), NO("S2"), place("p1", at="S1", t="10ms", noise=False))
    sim.run()
    tr = sim.trace
    assert tr.value_at("S1", 5 * MS) is True  # NC: no object, the contact is closed
    assert tr.falls("S1").tolist() == [11 * MS]  # the beam is cut one step after the placement
    assert tr.value_at("S1", 50 * MS) is False
    assert not tr.column("S2").any()  # NO, nothing at S2


# -- faults ----------------------------------------------------------------------------------------


def test_wire_break_on_an_nc_barrier_reads_object_present():
    sim = conveyor_sim(NC("S1"), NO("S2"), wire_break("S1", t="20ms"))
    sim.run()
    tr = sim.trace
    assert sim.plant.sensors["S1"] is False  # physically nothing is there
    assert tr.value_at("S1", 19 * MS) is True
    assert tr.falls("S1").tolist() == [20 * MS]  # reads like "object present" from the break on
    assert tr.value_at("S1", 99 * MS) is False
    assert [(e.t_ns, e.kind, e.subject) for e in tr.events_of(source="scenario")] == [(20 * MS, "break_wire", "S1")]


def test_wire_break_on_an_no_barrier_hides_an_object():
    sim = conveyor_sim(NO("S1"), NO("S2"), wire_break("S1", t="5ms"), place("p1", at="S1", t="10ms", noise=False))
    sim.run()
    assert sim.plant.sensors["S1"] is True
    assert not sim.trace.column("S1").any()


def test_stuck_at_one_and_zero_on_sensors_then_cleared():
    sim = conveyor_sim(
        NO("S1"),
        NO("S2"),
        stuck("S2", True, t="10ms"),
        clear("S2", t="30ms"),
        place("p1", at="S1", t="40ms", noise=False),
        stuck("S1", False, t="60ms"),
    )
    sim.run()
    tr = sim.trace
    assert tr.intervals("S2") == [(10 * MS, 30 * MS)]  # TRUE with nothing there, until cleared
    assert tr.intervals("S1") == [(41 * MS, 60 * MS)]  # the object is seen until S1 sticks at 0
    assert sim.plant.sensors["S1"] is True


def test_a_fault_named_by_its_tag_acts_on_the_signal():
    cpu = CPU({"START": Tag("%I0.0"), "S2": Tag("%I0.1"), "D1": Tag("%Q0.0")}, IDLE)
    sim = Simulation(cpu, Conv1(), [NO("S1", "START"), NO("S2"), NO("D1")], Scenario("s", stuck("START", True, t="0s")))
    sim.run("5ms")
    assert sim.wiring.faults["S1"].kind == "stuck"
    assert sim.trace.column("START").all()


def test_stuck_actuator_acts_at_once_and_clear_gives_the_program_back():
    scenario = Scenario("s", stuck("PUMP", True, t="10ms"), clear("PUMP", t="30ms"), duration="50ms")
    sim = tank_sim(scenario=scenario)
    sim.run()
    pump = [(t, v) for t, name, v in sim.plant.actuated if name == "PUMP"]
    assert pump == [(0, False), (10 * MS, True), (30 * MS, False)]  # the program writes FALSE throughout


def test_wire_break_on_an_analog_output_and_input():
    scenario = Scenario("s", wire_break("VALVE", t="20ms"), wire_break("LEVEL", t="20ms"), duration="30ms")
    sim = tank_sim(scenario=scenario)
    sim.run()
    valve = [(t, v) for t, name, v in sim.plant.actuated if name == "VALVE"]
    assert valve == [(0, 0.0), (1 * MS, 50.0), (20 * MS, 0.0)]
    assert sim.trace.value_at("LEVEL", 19 * MS) == 6912
    assert sim.trace.value_at("LEVEL", 20 * MS) == 32767  # S7 analog modules report overflow


def test_chatter_adds_exact_toggles_with_a_fixed_pattern():
    sim = panel_sim(
        chatter("TL", t="0s", transitions=(5, 5), width=("2ms", "2ms")), press("TL", t="100ms", hold="100ms")
    )
    sim.run()
    tr = sim.trace
    # 5 segments of 2 ms per change: the new level at once, then two bounces back to the old one
    assert tr.rises("TL").tolist() == [100 * MS, 104 * MS, 108 * MS, 202 * MS, 206 * MS]
    assert tr.falls("TL").tolist() == [102 * MS, 106 * MS, 200 * MS, 204 * MS, 208 * MS]
    assert tr.rises("LED").tolist() == [101 * MS, 105 * MS, 109 * MS, 203 * MS, 207 * MS]


def edges(seed: int, with_chatter: bool = True) -> tuple[list[int], list[int]]:
    actions = [press("TL", t="100ms", hold="200ms")]
    if with_chatter:
        actions.insert(0, chatter("TL", t="50ms"))
    sim = panel_sim(*actions, seed=seed)
    sim.run()
    return sim.trace.rises("TL").tolist(), sim.trace.falls("TL").tolist()


def test_chatter_is_deterministic_per_seed_and_varies_with_it():
    assert edges(1, with_chatter=False) == ([100 * MS], [300 * MS])
    first = edges(1)
    assert edges(1) == first
    assert edges(2) != first
    for seed in (1, 2, 3):
        rises, falls = edges(seed)
        changes = sorted(rises + falls)
        near_press = [t for t in changes if 100 * MS <= t < 150 * MS]
        near_release = [t for t in changes if 300 * MS <= t < 350 * MS]
        assert len(near_press) + len(near_release) == len(changes)  # bounces only right after a change
        assert len(near_press) in (3, 5) and len(near_release) in (3, 5)  # 3..5 bounces: 3 or 5 level changes
        assert len(rises) > 1


def test_chatter_without_a_change_does_nothing():
    sim = panel_sim(chatter("TL", t="0s"))
    sim.run()
    assert not sim.trace.column("TL").any()


# -- analog ----------------------------------------------------------------------------------------


def test_analog_input_and_output_are_scaled_to_the_raw_range():
    sim = tank_sim()
    sim.run("5ms")
    assert sim.cpu.inputs["LEVEL"] == 6912  # 250 mm of 0..1000 mm -> 27648 / 4
    assert sim.trace.column("LEVEL").tolist() == [6912.0] * 5  # the scans 0..5 ms
    assert sim.trace.types["LEVEL"] == "int"
    # the program writes 13824 (half of 27648): the valve opens to 50 %
    assert sim.plant.actuated == [(0, "VALVE", 0.0), (0, "PUMP", False), (1 * MS, "VALVE", 50.0)]


def test_analog_with_another_raw_range_and_clipping():
    sim = tank_sim(analog("LEVEL", raw=(0, 10_000)))
    sim.run("3ms")
    assert sim.cpu.inputs["LEVEL"] == 2500
    sim = tank_sim(level=2000.0)  # twice the range: 55296 raw, clipped to the 16-bit word
    sim.run("3ms")
    assert sim.cpu.inputs["LEVEL"] == 32767


def test_stuck_analog_input():
    sim = tank_sim(scenario=Scenario("s", stuck("LEVEL", 1234, t="2ms"), duration="5ms"))
    sim.run()
    assert sim.trace.column("LEVEL").tolist() == [6912.0, 6912.0, 1234.0, 1234.0, 1234.0]


def noisy_levels(seed: int) -> list[float]:
    sim = tank_sim(analog("LEVEL", noise=50.0), seed=seed)
    sim.run("300ms")
    return sim.trace.column("LEVEL").tolist()


def test_analog_noise_is_seeded():
    a = noisy_levels(3)
    assert len(a) == 300
    assert noisy_levels(3) == a
    assert noisy_levels(4) != a
    assert all(v == int(v) for v in a)  # raw values are integers
    assert abs(statistics.mean(a) - 6912) < 15  # 300 samples of sigma 50: standard error 2.9
    assert 35 < statistics.stdev(a) < 65
    assert len(set(a)) > 50


# -- validation ------------------------------------------------------------------------------------


@pytest.fixture
def conveyor_cpu():
    tags = {
        "S1": Tag("%I0.0"),
        "S2": Tag("%I0.1"),
        "S2B": Tag("%I0.1"),  # overlaps S2: legal in the tag table, not on a terminal
        "D1": Tag("%Q0.0"),
        "M": Tag("%M0.0"),
        "W": Tag("%IW2", Int),
        "H": Int(0),
    }
    return CPU(tags, IDLE)


@pytest.mark.parametrize(
    ("wires", "message"),
    [
        ([NO("S1X")], r"^wiring: CONV1 has no signal 'S1X'; did you mean 'S1'\?; its signals: S1, S2, D1$"),
        ([NO("S9")], r"^wiring: CONV1 has no signal 'S9'; its signals: S1, S2, D1$"),
        ([NO("S1", "S1X")], r"^wiring: S1 goes to tag 'S1X', which is not in the tag table; did you mean 'S1'\?$"),
        ([NO("S1", "D1")], r"^wiring: sensor S1 is wired to D1 at %Q0.0; sensors go to inputs \(%I\)$"),
        ([NO("S1", "M")], r"^wiring: sensor S1 is wired to M at %M0.0; sensors go to inputs \(%I\)$"),
        ([NO("D1", "S1")], r"^wiring: actuator D1 is wired to S1 at %I0.0; actuators are driven by outputs \(%Q\)$"),
        ([NO("S1"), NO("S2", "S1")], r"^wiring: tag 'S1' is wired to both S1 and S2$"),
        ([NO("S1"), NO("S1", "S2")], r"^wiring: signal 'S1' is wired twice$"),
        ([NO("S1", "S2"), NO("S2", "S2B")], r"^wiring: address %I0.1 is already used by S1; S2 needs an address"),
        ([NO("S1", "H")], r"^wiring: tag 'H' has no address; a wire needs an %I or %Q tag$"),
        ([NO("S1", "W")], r"^wiring: S1 is a Boolean signal but W is Int$"),
        ([Wire("S1", "S1", "XX")], r"^wiring: S1: contact must be 'NO' or 'NC', not 'XX'$"),
    ],
    ids=[
        "unknown-signal-suggestion",
        "unknown-signal",
        "tag-not-in-table",
        "sensor-on-Q",
        "sensor-on-M",
        "actuator-on-I",
        "tag-twice",
        "signal-twice",
        "address-twice",
        "no-address",
        "type",
        "contact",
    ],
)
def test_wiring_errors(conveyor_cpu, wires, message):
    with pytest.raises(WiringError, match=message):
        Wiring(Conv1(), conveyor_cpu.table, wires)
    # the same error stops a simulation before it starts
    with pytest.raises(WiringError, match=message):
        Simulation(conveyor_cpu, Conv1(), wires)


def test_a_fault_on_a_name_that_is_not_wired():
    cpu = CPU({"S1": Tag("%I0.0"), "S2": Tag("%I0.1"), "D1": Tag("%Q0.0")}, IDLE)
    wiring = Wiring(Conv1(), cpu.table, [NO("S1"), NO("S2"), NO("D1")])
    with pytest.raises(WiringError, match=r"^no wired signal or tag 'S3'$"):
        wiring.stick("S3", True)
    with pytest.raises(WiringError, match=r"^no wired signal or tag 's2'; did you mean 'S2'\?$"):
        wiring.break_wire("s2")


def test_describe_lists_the_wires():
    cpu = CPU(TANK_TAGS, TANK_PROGRAM)
    wiring = Wiring(Tank(), cpu.table, [analog("LEVEL"), NC("FULL"), NO("PUMP")])
    rows = wiring.describe()
    assert [(r["signal"], r["tag"], r["contact"], r["direction"]) for r in rows] == [
        ("LEVEL", "LEVEL", "analog", "sensor"),
        ("FULL", "FULL", "NC", "sensor"),
        ("PUMP", "PUMP", "NO", "actuator"),
    ]


def test_each_step_reads_through_the_fault_path_exactly_while_a_fault_is_injected():
    """``Wiring.step_inputs`` (what the simulator calls in every step) is the generated fault-free copy until a
    fault is injected, ``read_inputs`` while one is, and the copy again once every fault is cleared; both give
    the same levels where no fault acts."""
    sim = tank_sim()
    wiring = sim.wiring
    assert wiring.step_inputs is wiring._copy_inputs
    fast: dict = {}
    wiring.step_inputs(fast, 0)
    assert fast == {"LEVEL": 6912, "FULL": False}
    for inject in (
        lambda: wiring.stick("FULL", True),
        lambda: wiring.break_wire("FULL"),
        lambda: wiring.chatter("FULL"),
    ):
        inject()
        assert wiring.step_inputs == wiring.read_inputs
        wiring.clear("FULL")
        assert wiring.step_inputs is wiring._copy_inputs
    wiring.stick("FULL", True)
    wiring.stick("LEVEL", 100)
    wiring.clear("FULL")  # one fault left: still the fault path
    assert wiring.step_inputs == wiring.read_inputs
    faulted: dict = {}
    wiring.step_inputs(faulted, 0)
    assert faulted == {"LEVEL": 100, "FULL": False}
    wiring.clear()
    assert wiring.step_inputs is wiring._copy_inputs
