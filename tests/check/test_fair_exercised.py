"""Fair grades (plcsim.check.exercised): a check earns its points only if the run showed the behaviour it
guards. A program that does nothing, whose CPU stops at 0 s, or that has no OB1 earns nothing on the
conveyor exercises (before, 6/12 on 4.3.6, 7/21 on 4.3.7, 15/25 on 4.3.9, from safety checks that
held because nothing moved); the shipped solutions still grade as their kinds say
(tests/course/test_exercises.py)."""

from __future__ import annotations

import csv
import json
from pathlib import Path
from xml.etree import ElementTree as ET

import pytest

from exercises import get
from plcsim.check import action, all_of, always, never, off, rises, same
from plcsim.check.base import Context
from plcsim.check.exercised import Activity, unprovoked
from plcsim.core.errors import ExerciseError
from plcsim.exercise.model import Exercise
from plcsim.grading.grader import grade, grade_sandboxed
from plcsim.grading.report import write_gradebook
from plcsim.scenario.planning import Scenario
from plcsim.scenario.verbs import press
from plcsim.trace.facade import Trace

DOES_NOTHING = "def nothing(t):\n    pass\n\n\nOB1 = [nothing]\n"
STOPS_AT_ONCE = "def spin(t):\n    while True:\n        pass\n\n\nOB1 = [spin]\n"  # the watchdog: STOP in scan 1
NO_OB1 = "X = Int(0)\n\n\ndef network(t):\n    t.X = 1\n"

# exercise -> (maximum, checks that held only because nothing moved: earned before, not exercised now)
IDLE_PASSES = {"4.3.6": (12.0, 6), "4.3.7": (21.0, 7), "4.3.9": (33.0, 23)}  # 4.3.9: with "a hand at D3_OS"


def program(tmp_path: Path, name: str, source: str) -> Path:
    path = tmp_path / f"{name}.py"
    path.write_text(source, encoding="utf-8")
    return path


@pytest.mark.parametrize("number", sorted(IDLE_PASSES))
@pytest.mark.parametrize(("name", "source"), [("nothing", DOES_NOTHING), ("stop", STOPS_AT_ONCE)])
def test_an_idle_program_earns_nothing(number, name, source, tmp_path):
    maximum, idle_passes = IDLE_PASSES[number]
    report = grade(get(number), program(tmp_path, name, source))
    assert report.error is None
    assert (report.score, report.max_score, report.passed) == (0.0, maximum, False)
    assert len(report.not_exercised()) == idle_passes
    assert all(c.points == 0 and not c.passed for c in report.not_exercised())
    assert any("drove no output or tag in any scenario" in w for w in report.warnings)
    if name == "stop":
        assert all(run.cpu_mode == "STOP" for run in report.runs)
        assert all("[the CPU stopped: 0 ns: cycle time monitoring" in c.message for c in report.not_exercised())


@pytest.mark.parametrize("number", sorted(IDLE_PASSES))
def test_a_program_without_ob1_earns_nothing_and_says_why(number, tmp_path):
    report = grade(get(number), program(tmp_path, "no_ob1", NO_OB1))
    assert (report.score, report.max_score, report.error_kind) == (0.0, IDLE_PASSES[number][0], "program error")
    assert "OB1" in report.error


def test_a_safety_check_on_a_signal_the_program_never_drives_earns_nothing():
    """4.3.7 wrong-scan-order never raises ALARM: "no false alarm" held, but proves nothing."""
    ex = get("4.3.7")
    report = grade(ex, ex.solution("wrong-scan-order").path, scenarios=["three objects"])
    result = report.result("no false alarm in normal operation")
    assert (result.status, result.points, result.max_points) == ("not exercised", 0.0, 1.0)
    assert "the program never drove ALARM in any scenario" in result.message
    assert report.result("the belt never runs while S2 sees an object").status == "passed"  # D1 was driven


def test_the_reports_carry_the_status(tmp_path):
    """In the sandbox too; JSON, JUnit (``<skipped>``) and the gradebook name it."""
    report = grade_sandboxed(get("4.3.6"), program(tmp_path, "nothing", DOES_NOTHING))
    assert (report.score, report.max_score, len(report.not_exercised())) == (0.0, 12.0, 6)
    data = json.loads(report.to_json())
    assert sorted({c["status"] for c in data["checks"]}) == ["failed", "not exercised"]
    root = ET.fromstring(report.to_junit())
    assert (root.get("tests"), root.get("failures"), root.get("skipped"), root.get("errors")) == ("12", "6", "6", "0")
    case = root.find(".//testcase[@name='no object falls off the belt']")
    assert case.find("skipped").get("message").startswith("not exercised: the program drove no output")
    write_gradebook([report], tmp_path / "grades.csv")
    (row,) = csv.DictReader((tmp_path / "grades.csv").open(encoding="utf-8"))
    assert row["five objects: no object falls off the belt"] == "not exercised"
    assert row["five objects: every loaded object arrives at S2"] == "FAIL"


def trace(rows: list[tuple[bool, bool, bool]]) -> Trace:
    kinds = {"S1": "input", "ACK": "memory", "D1": "output"}
    tr = Trace(list(kinds), kinds=kinds, types=dict.fromkeys(kinds, "bool"))
    for k, row in enumerate(rows):
        tr.add_row(k * 1_000_000, (k + 1) * 1_000_000, 1, row)
    return tr


def test_what_counts_as_driven():
    belt = never(all_of("D1", off("S1")))
    pressed = trace([(False, False, False), (True, True, False), (False, False, False)])
    assert Activity.of([pressed], written_by_scenario={"ACK"}).driven == frozenset()  # the scenario pressed ACK
    assert Activity.of([pressed], written_by_scenario=set()).driven == {"ACK"}
    on_from_start = trace([(False, False, True)] * 3)  # an output on from the first scan was driven
    assert Activity.of([on_from_start], written_by_scenario=set()).unexercised(belt) is None
    idle = Activity.of([pressed], written_by_scenario=set())
    assert idle.unexercised(belt) == "the program never drove D1 in any scenario"
    assert idle.unexercised(never("S1")) is None  # reads no signal a program writes: any activity counts


def test_exercised_by_asks_for_the_behaviour_in_each_scenario():
    check = never(all_of("D1", off("S1"))).exercised_by(rises("S1"))
    assert check.names().signals == ("D1", "S1")  # validated when the exercise is loaded
    quiet = Context.of(trace([(False, False, False)] * 3))
    busy = Context.of(trace([(False, False, False), (True, False, True), (False, False, False)]))
    assert unprovoked(check, quiet) == "S1 rises never happened in this scenario"
    assert unprovoked(check, busy) is None


def panel_exercise(*checks) -> Exercise:
    led = get("4.3.1")
    return Exercise(
        number="9.1.1",
        slug="lamp-test",
        title="lamp test",
        task="LED follows the button",
        io=led.io,
        rig=led.rig,
        scenarios=[
            Scenario("presses", press("TLACIDLO", t="0.5s", hold="0.3s"), duration="2s"),
            Scenario("idle", duration="1s"),
        ],
        checks=list(checks),
        solutions=[],
    )


def test_exercised_by_in_a_graded_exercise():
    """The generic rule counts the idle scenario (the LED was driven in the other); the opt-in does not."""
    plain = never(all_of("LED", off("TLACIDLO"))).named("no light without a press")
    opted = (
        never(all_of("LED", off("TLACIDLO"))).named("no light, where pressed").exercised_by(action("press", "TLACIDLO"))
    )
    ex = panel_exercise(plain, opted, always(same("LED", "TLACIDLO")).named("LED follows"))
    report = grade(ex, get("4.3.1").reference.path)
    status = {(c.scenario, c.check): c.status for c in report.checks}
    assert status[("idle", "no light without a press")] == "passed"
    assert status[("idle", "no light, where pressed")] == "not exercised"
    assert status[("presses", "no light, where pressed")] == "passed"
    assert (report.score, report.max_score) == (5.0, 6.0)
    assert "press TLACIDLO never happened in this scenario" in report.result("no light, where pressed").message


def test_a_typo_in_exercised_by_is_the_exercise_s_error():
    with pytest.raises(ExerciseError, match="LDE"):
        panel_exercise(never("LED").exercised_by(rises("LDE")))
