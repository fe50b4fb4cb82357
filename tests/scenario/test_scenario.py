"""Scenarios (plcsim.scenario, carried out by the simulator): seeded time ranges, triggers, the name
checks before a run (with the file and line of the action and the valid choices), actions that fail
during a run, and the plant faults (shifted sensor, jammed motor).
"""

from __future__ import annotations

import random
import re
import sys
from pathlib import Path

import pytest

from exercises import get
from plants import Conv1, Panel
from plcsim import CPU, CPUConfig, Simulation, Tag
from plcsim.scenario.planning import Scenario, plan
from plcsim.scenario.verbs import (
    ScenarioError,
    TimeSpec,
    after_event,
    free_motor,
    held,
    jam,
    jam_motor,
    place,
    press,
    remove,
    shift_sensor,
    stuck,
    write,
)
from plcsim.sim.wiring import NO

MS = 1_000_000
S = 1_000_000_000
IDLE = "def OB1(t):\n    pass\n"
HERE = re.escape(__file__)


def here() -> int:
    """The caller's line number."""
    return sys._getframe(1).f_lineno


def panel_sim(scenario: Scenario, seed: int = 0) -> Simulation:
    cpu = CPU({"TL": Tag("%I0.0"), "LED": Tag("%Q0.0")}, "def OB1(t):\n    t.LED = t.TL\n")
    plant = Panel(buttons=("TL",), switches=(), lamps=("LED",))
    return Simulation(cpu, plant, [NO("TL"), NO("LED")], scenario, seed=seed)


def conveyor_sim(scenario: Scenario, program: str = IDLE, seed: int = 0) -> Simulation:
    cpu = CPU({"S1": Tag("%I0.0"), "S2": Tag("%I0.1"), "D1": Tag("%Q0.0"), "ACK": Tag("%M0.0")}, program)
    return Simulation(cpu, Conv1(), [NO("S1"), NO("S2"), NO("D1")], scenario, seed=seed)


def reference_sim(scenario: Scenario, seed: int = 1) -> Simulation:
    """Exercise 4.3.5's reference (S1 sets D1, S2 resets it) on CONV1."""
    ex = get("4.3.5")
    cpu = CPU(ex.tag_table(), ex.reference.program(), CPUConfig(seed=seed))
    sim = Simulation(cpu, Conv1(), ex.wires(), scenario, seed=seed)
    sim.run()
    return sim


# -- times -----------------------------------------------------------------------------------------


def test_timespec_parsing():
    assert TimeSpec.parse("2s") == TimeSpec(2 * S, 2 * S)
    assert TimeSpec.parse("2s..3s") == TimeSpec(2 * S, 3 * S)
    assert TimeSpec.parse(" 300ms .. 1.5s ") == TimeSpec(300 * MS, 1500 * MS)
    assert TimeSpec.parse(7) == TimeSpec(7, 7)
    assert str(TimeSpec.parse("2s..3s")) == "2 s..3 s"
    assert str(TimeSpec.parse("500ms")) == "500 ms"
    with pytest.raises(ScenarioError, match=r"^time range '3s..2s' runs backwards$"):
        TimeSpec.parse("3s..2s")


def test_a_fixed_time_draws_nothing():
    rng = random.Random(1)
    state = rng.getstate()
    assert TimeSpec.parse("2s").draw(rng) == 2 * S
    assert rng.getstate() == state


def drawn(scenario: Scenario, seed: int) -> list[int | None]:
    return [p.at_ns for p in plan(scenario, random.Random(seed))]


def test_ranges_are_drawn_per_seed():
    scenario = Scenario("r", press("TL", t="1s..2s", hold="10ms..50ms"), press("TL", t="3s..4s"), duration="5s")
    one = drawn(scenario, 1)
    assert drawn(scenario, 1) == one
    assert drawn(scenario, 2) != one
    for seed in range(20):
        press1, release1, press2 = drawn(scenario, seed)
        assert 1 * S <= press1 <= 2 * S
        assert press1 + 10 * MS <= release1 <= press1 + 50 * MS  # the hold counts from the drawn press
        assert 3 * S <= press2 <= 4 * S
    assert len({drawn(scenario, seed)[0] for seed in range(20)}) == 20


def test_a_drawn_time_is_applied_at_the_next_step():
    scenario = Scenario("r", press("TL", t="10ms..90ms", hold="5ms..9ms"), duration="200ms")
    for seed in (1, 2, 3):
        press_at, release_at = drawn(scenario, seed)
        sim = panel_sim(scenario, seed=seed)
        sim.run()
        steps = [-(-press_at // MS) * MS, -(-release_at // MS) * MS]  # rounded up to the 1 ms step grid
        assert [e.t_ns for e in sim.trace.events_of(source="scenario")] == steps
        assert sim.trace.rises("TL").tolist() == [steps[0]]
        assert sim.trace.falls("TL").tolist() == [steps[1]]


def test_the_exercise_scenarios_change_with_the_seed():
    ex = get("4.3.1")
    times = {}
    for seed in (1, 2):
        sim = ex.simulation(ex.reference.program(), "presses", seed=seed)
        sim.run()
        times[seed] = sim.trace.rises("TLACIDLO").tolist()
        assert len(times[seed]) == 12
    assert times[1] != times[2]


# -- triggers --------------------------------------------------------------------------------------


def test_held_and_after_event_triggers_in_exercise_4_3_5():
    sim = reference_sim(get("4.3.5").scenario("three objects"), seed=1)
    tr = sim.trace
    entered_s2 = [e.t_ns for e in tr.events_of("part entered", "S2")]
    removed = [e.t_ns for e in tr.events_of("remove", source="scenario")]
    placed = [e.t_ns for e in tr.events_of("place", source="scenario")]
    assert len(entered_s2) == len(removed) == len(placed) == 3
    # remove(pk, when=held("S2", "1s")): exactly 1 s after S2 was interrupted
    assert removed == [t + 1 * S for t in entered_s2]
    # place(p(k+1), when=after_event("part removed", pk), delay="1s..2s")
    for gone, nxt in zip(removed[:2], placed[1:]):
        assert 1 * S <= nxt - gone <= 2 * S + 1 * MS
    assert [e.part for e in tr.events_of("remove", source="scenario")] == ["p1", "p2", "p3"]


def test_held_waits_for_the_sensor_value_and_rearms():
    scenario = Scenario(
        "s",
        place("p1", at="S2", t="100ms", noise=False),
        remove("p1", t="300ms"),
        place("p2", at="S2", t="400ms", noise=False),
        write("ACK", True, when=held("S2", "500ms")),  # S2 held 200 ms, then 700 ms
        duration="2s",
    )
    sim = conveyor_sim(scenario)
    sim.run()
    writes = sim.trace.events_of("write", source="scenario")
    assert [e.t_ns for e in writes] == [401 * MS + 500 * MS]
    assert sim.cpu.read("ACK") is True


def test_held_for_false():
    scenario = Scenario(
        "s",
        place("p1", at="S2", t="0s", noise=False),
        remove("p1", t="200ms"),
        write("ACK", True, when=held("S2", "100ms", value=False)),
        duration="1s",
    )
    sim = conveyor_sim(scenario)
    sim.run()
    assert [e.t_ns for e in sim.trace.events_of("write", source="scenario")] == [301 * MS]


def test_part_actions_wait_until_the_part_exists():
    scenario = Scenario(
        "wait",
        place("p1", at="S2", t="100ms", noise=False),
        remove("p2", when=held("S2", "500ms")),  # S2 is held by p1 long before p2 exists
        place("p2", at="S1", t="2s", noise=False),
        place(
            "p3", at="belt", offset_mm=150.0, when=after_event("part removed", "p2"), delay="100ms..300ms", noise=False
        ),
        duration="4s",
    )
    sim = conveyor_sim(scenario, seed=1)
    sim.run()
    tr = sim.trace
    removed = tr.events_of("remove", source="scenario")
    assert [(e.t_ns, e.part) for e in removed] == [(2_501 * MS, "p2")]  # armed from the step after p2 came
    assert [e.part for e in tr.events_of("part removed")] == ["p2"]
    p3 = [e.t_ns for e in tr.events_of("place", "p3", source="scenario")]
    assert len(p3) == 1 and 2_601 * MS <= p3[0] <= 2_801 * MS


# -- names checked before the run -------------------------------------------------------------------


def scenario_error(action) -> str:
    with pytest.raises(ScenarioError) as info:
        conveyor_sim(Scenario("bad", action))
    return str(info.value)


def test_unknown_station_names_the_line_and_the_choices():
    line = here() + 1
    action = place("p1", at="S3", t="1s")
    message = scenario_error(action)
    assert re.fullmatch(
        rf"{HERE}:{line}: scenario 'bad': place 'p1' at S3 at 1 s: no station 'S3'; "
        r"valid: S1, S2, belt",
        message,
    ), message


@pytest.mark.parametrize(
    ("make", "expected"),
    [
        (
            lambda: place("p1", at="s1", t="1s"),
            r"place 'p1' at s1 at 1 s: no station 's1'; did you mean 'S1'\?; "
            r"valid: S1, S2, belt",
        ),
        (lambda: press("START", t="1s"), r"press START at 1 s: no button or switch 'START'; valid: none"),
        (
            lambda: write("ACKX", True, t="1s"),
            r"write ACKX = True at 1 s: no tag 'ACKX'; did you mean 'ACK'\?; "
            r"valid: S1, S2, D1, ACK",
        ),
        (lambda: remove("p9", t="1s"), r"remove 'p9' at 1 s: no part or station 'p9'; valid: S1, S2, belt"),
        (lambda: jam("p9", t="1s"), r"jam 'p9' at 1 s: no part 'p9'; valid: none"),
        (lambda: stuck("S3", True, t="1s"), r"stick S3 at True at 1 s: no wired signal 'S3'; valid: S1, S2, D1"),
        (lambda: jam_motor("M1", t="1s"), r"jam motor M1 at 1 s: no motor 'M1'; valid: D1"),
        (
            lambda: write("ACK", True, when=held("S7", "1s")),
            r"write ACK = True when S7 has been interrupted/actuated for 1 s: no signal to wait for 'S7'; "
            r"valid: S1, S2",  # a trigger waits for a plant sensor: the actuator D1 is never polled
        ),
    ],
    ids=["station-suggestion", "button", "tag", "remove", "jam", "wired-signal", "motor", "trigger-signal"],
)
def test_bad_names(make, expected):
    message = scenario_error(make())
    # the place is the line that built the action (the lambda in the parameter list above)
    assert re.fullmatch(rf"{HERE}:\d+: scenario 'bad': {expected}", message), message


def test_a_bad_name_in_an_exercise_scenario_stops_before_the_run():
    ex = get("4.3.5")
    line = here() + 1
    bad = Scenario("typo", place("p1", at="S1", t="0.5s"), remove("p1", when=held("S22", "1s")), duration="2s")
    with pytest.raises(
        ScenarioError,
        match=rf"^{HERE}:{line}: scenario 'typo': remove 'p1' when S22 .*"
        r"no signal to wait for 'S22'; did you mean 'S2'\?",
    ):
        ex.simulation(ex.reference.program(), bad)


def test_bad_times_are_reported_where_they_were_written():
    line = here() + 2
    with pytest.raises(ScenarioError, match=rf"^{HERE}:{line}: press TL: give exactly one of t='2s' or when=held"):
        press("TL")
    line = here() + 2
    with pytest.raises(ScenarioError, match=rf"^{HERE}:{line}: press TL: give exactly one of t="):
        press("TL", t="1s", when=held("S1"))
    line = here() + 2
    with pytest.raises(ScenarioError, match=rf"^{HERE}:{line}: press TL: cannot read duration '2 parsecs'"):
        press("TL", t="2 parsecs")
    line = here() + 2
    with pytest.raises(ScenarioError, match=rf"^{HERE}:{line}: press TL: time range '3s..2s' runs backwards$"):
        press("TL", t="3s..2s")
    with pytest.raises(ScenarioError, match=r"hold= needs a fixed t="):
        press("TL", when=held("S1"), hold="1s")
    with pytest.raises(ScenarioError, match=r"^a scenario holds actions such as press\(...\) or place\(...\), not 3$"):
        Scenario("x", 3)


def test_describe_and_defined_at():
    line = here() + 1
    actions = press("TL", t="1s..2s", hold="100ms")
    assert [a.describe() for a in actions] == ["press TL at 1 s..2 s", "release TL 100 ms after the press"]
    assert actions[0].defined_at == f"{__file__}:{line}"
    trig = place("p2", at="S1", when=after_event("part removed", "p1"), delay="1s..2s")
    assert trig.describe() == "place 'p2' at S1 after 'part removed' of p1 + 1 s..2 s"


# -- actions that fail during the run --------------------------------------------------------------


def test_removing_a_part_that_fell_off_is_recorded_not_raised():
    line = here() + 4
    scenario = Scenario(
        "fall",
        place("p1", at="S2", t="100ms", noise=False),
        remove("p1", t="3s"),
        place("p2", at="S1", t="3.2s", noise=False),
        place("p3", at="S1", t="3.2s", noise=False),  # S1 is taken by p2
        duration="4s",
    )
    sim = conveyor_sim(scenario, program="def OB1(t):\n    t.D1 = True\n")
    sim.run()  # no exception
    tr = sim.trace
    assert sim.now == 4 * S
    assert len(tr.events_of("part fell off")) == 1
    failed = tr.events_of("action failed", source="scenario")
    assert [(e.t_ns, e.subject) for e in failed] == [(3 * S, "p1"), (3_200 * MS, "p3")]
    assert failed[0].detail.startswith(f"remove 'p1' at 3 s ({Path(__file__).name}:{line}): ")  # no folder: see
    # test_a_trace_is_the_same_wherever_the_program_file_sits; the file and line still name the action
    assert "p1" in failed[0].detail[len("remove 'p1' at 3 s (") :]
    assert "cannot place a part at S1" in failed[1].detail
    assert [e.kind for e in tr.events_of(source="scenario")] == ["place", "action failed", "place", "action failed"]


# -- plant faults ----------------------------------------------------------------------------------


def test_a_shifted_sensor_sees_the_part_earlier():
    normal = reference_sim(Scenario("n", place("p1", at="S1", t="0.5s", noise=False), duration="6s"))
    shifted = reference_sim(
        Scenario("s", shift_sensor("S2", -100.0, t="0s"), place("p1", at="S1", t="0.5s", noise=False), duration="6s")
    )
    transport = (normal.trace.rises("S2") - normal.trace.rises("S1")).tolist()
    short = (shifted.trace.rises("S2") - shifted.trace.rises("S1")).tolist()
    assert abs(transport[0] - 4_830 * MS) <= 5 * MS  # the plant's documented 4.83 s
    assert abs((transport[0] - short[0]) - 2 * S) <= 2 * MS  # 100 mm at 50 mm/s


def test_a_jammed_motor_holds_the_part():
    normal = reference_sim(Scenario("n", place("p1", at="S1", t="0.5s", noise=False), duration="9s"))
    jammed = reference_sim(
        Scenario(
            "j",
            place("p1", at="S1", t="0.5s", noise=False),
            jam_motor("D1", t="1s"),
            free_motor("D1", t="3s"),
            duration="9s",
        )
    )
    assert [(e.t_ns, e.subject) for e in jammed.trace.events_of("motor jammed")] == [(1 * S, "D1")]
    delay = int(jammed.trace.rises("S2")[0] - normal.trace.rises("S2")[0])
    assert abs(delay - 2 * S) <= 5 * MS  # the belt stood still for 2 s while D1 was on
    assert jammed.trace.value_at("D1", 2 * S) is True
