"""The Tecomat on the scenario timeline: the controller's own verbs (``interrupt`` raising the event
processes P41..P48, ``set_clock`` for the real-time clock), refused before a run on a controller without
them; and the Tecomat exercises T-01.. found, run and graded as the S7 ones are."""

from __future__ import annotations

from pathlib import Path

import pytest

import exercises
from plants import Panel
from plcsim import CPU, Program, Simulation, Tag
from plcsim.check import action, count, final
from plcsim.controllers.tecomat.verbs import INTERRUPT, interrupt, set_clock
from plcsim.core.errors import ExerciseError
from plcsim.exercise.model import IO, Exercise, Solution
from plcsim.frontends import read_program
from plcsim.frontends.il import program_text
from plcsim.grading.report import Report
from plcsim.grading.run import run_scenarios
from plcsim.grading.scoring import evaluate
from plcsim.scenario.planning import Scenario
from plcsim.scenario.verbs import ScenarioError, switch
from plcsim.tags.types import Byte

ROOT = Path(__file__).resolve().parents[2]
EVENTS = ROOT / "examples" / "tecomat" / "p41_event_counter.il"


def events_scenario() -> Scenario:
    return Scenario(
        "events",
        interrupt(1, t="5ms"),  # before the program enables source 1: ignored
        switch("povol", True, t="10ms"),
        interrupt(1, t="100ms"),
        interrupt(1, t="200.5ms"),
        interrupt(1, t="300ms"),
        switch("povol", False, t="400ms"),
        interrupt(1, t="500ms"),  # disabled again: ignored
        interrupt(2, t="600ms"),  # no P42 in the program: nothing runs
        duration="700ms",
    )


def test_the_interrupt_verb_runs_p41_at_the_next_turnaround_while_its_source_is_enabled():
    sim = Simulation(read_program(EVENTS).controller(), None, None, events_scenario())
    sim.run()
    tr = sim.trace
    assert [round(e.t_ns / 1e6, 1) for e in tr.events_of("interrupt", None, "scenario")] == [
        5,
        100,
        201,
        300,
        500,
        600,
    ]  # at the step after
    assert [e.subject for e in tr.events_of("interrupt")] == ["1"] * 5 + ["2"]
    counted = tr.times[rises_of(tr.column("udalosti"))] // 1_000_000
    assert counted.tolist() == [100, 201, 300]  # the cycle starting at or after the raise runs P41 (1 ms cycles)
    assert tr.column("udalosti")[-1] == 3 and sim.cpu.peek("Y0") == 3


def rises_of(column) -> list[int]:
    return [k for k in range(1, len(column)) if column[k] > column[k - 1]]


def test_a_controller_verb_on_the_s7_cpu_is_refused_before_the_run_naming_the_line():
    cpu = CPU({"povol": Tag("%I0.0")}, Program.from_source("def OB1(t):\n    pass\n"))
    line = events_scenario.__code__.co_firstlineno + 3
    with pytest.raises(ExerciseError) as info:
        Simulation(cpu, None, None, events_scenario())
    message = str(info.value)
    assert f"{__file__}:{line}: scenario 'events': raise interrupt source 1 (P41) at 5 ms" in message
    assert "the S7-1200 cannot do this (a verb of the Tecomat NS950 controller (.il programs)" in message


def test_an_interrupt_source_the_tecomat_lacks_is_refused():
    with pytest.raises(ScenarioError, match=r"interrupt\(9\): the sources are 1\.\.8 \(P41\.\.P48\)"):
        interrupt(9, t="1s")
    scenario = Scenario("nine", INTERRUPT("9", t="1ms"), duration="10ms")
    with pytest.raises(ExerciseError, match=r"no interrupt source '9'; valid: 1, 2, 3, 4, 5, 6, 7, 8"):
        Simulation(read_program(EVENTS).controller(), None, None, scenario)


def test_set_clock_sets_the_real_time_clock_the_program_reads_in_s():
    program = program_text("LD S8\nWR Y0\nLD S7\nWR Y1\n", "clock.il")
    scenario = Scenario("clock", set_clock("10:29:59", t="1s"), duration="2.5s")
    sim = Simulation(program.controller({"H": Tag("%QB0", Byte), "M": Tag("%QB1", Byte)}), None, None, scenario)
    sim.run()
    assert (sim.trace.value_at("H", 999_000_000), sim.trace.value_at("M", 999_000_000)) == (8, 0)  # rtc_start 08:00
    assert (sim.trace.value_at("H", 1_100_000_000), sim.trace.value_at("M", 1_100_000_000)) == (10, 29)
    assert (sim.cpu.peek("S8"), sim.cpu.peek("S7")) == (10, 30)  # it runs on: 10:30:00.5 at the end (2.5 s)


def test_an_exercise_may_count_the_controller_s_actions_and_grades_an_il_program():
    exercise = Exercise(
        number="9.9.41",
        slug="events",
        title="events",
        task="count the events",
        io=[IO("povol", "enable switch", "Bool", "%I0.0", "NO"), IO("udalosti", "count", "Word", "%MW20")],
        rig=lambda: Panel(buttons=(), switches=("povol",), lamps=()),
        scenarios=[events_scenario()],
        checks=[
            count(action("interrupt", "1")).equals(5).named("five events of source 1"),
            final("udalosti").equals(3).named("three counted"),
        ],
        solutions=[Solution("reference", EVENTS)],
    )
    program = read_program(EVENTS)
    runs, analysis = run_scenarios(exercise, program, seed=1)
    report = evaluate(exercise, runs, analysis, Report(exercise.number, exercise.title, "p41", seed=1))
    assert report.error is None and not report.failed() and report.score == report.max_score == 2


@pytest.mark.parametrize("name", ["T-01", "t-01", "tecomat-start-stop"])
def test_the_tecomat_exercises_are_found_by_id_in_any_case_and_by_slug(name):
    assert exercises.get(name).number == "T-01"


def test_the_tecomat_exercises_ship_il_programs_only():
    tecomat = [e for e in exercises.all_exercises() if e.number.startswith("T-")]
    assert [e.number for e in tecomat] == sorted(e.number for e in tecomat) and len(tecomat) >= 4
    for exercise in tecomat:
        assert {s.path.suffix for s in exercise.solutions} == {".il"}
        assert sum(s.kind == "wrong" for s in exercise.solutions) >= 2


@pytest.mark.xdist_group("sandbox")
def test_the_grader_s_sandbox_grades_t05_whose_scenario_sets_the_tecomat_s_clock():
    """The sandbox's trusted probe runs on the S7, which cannot set a Tecomat clock: it must leave the
    controller's verbs out (it once made every T-05 grade a grader error)."""
    from plcsim.grading.grader import grade_sandboxed

    exercise = exercises.get("T-05")
    graded = {s.name: grade_sandboxed(exercise, s.path, seed=1, scenarios=s.scenarios) for s in exercise.solutions}
    assert graded["reference"].passed and not graded["reference"].error
    assert not graded["wrong-printed-constants"].passed and not graded["wrong-printed-constants"].error
