"""Fair to the student: no scenario grades a situation the task rules out, unless the task says what must happen
then (issue 27).

Each exercise states its operating conditions with the task's words (``Exercise(conditions=[assumes(...)])``); a
scenario that leaves one declares it (``Scenario(outside={words: the task's words for what must happen then})``), as
one that injects a fault declares ``FAULTS``. The words are checked when the exercise loads; the faults here, and
whether a scenario stays inside a condition depends on the run, so every exercise's reference runs every scenario,
on the two seeds the course is graded with in its tests.
"""

from __future__ import annotations

import pytest

from exercises import all_exercises, get
from plcsim.check import FAULTS, assumes, fault_problems, parts_at_once, undeclared_breaks
from plcsim.core.errors import ExerciseError
from plcsim.exercise import Exercise
from plcsim.scenario import Scenario, after_event, held, place, remove, stuck

EXERCISES = all_exercises()
WITH_CONDITIONS = [ex for ex in EXERCISES if ex.conditions]
CASES = [(ex, s.name, seed) for ex in WITH_CONDITIONS for s in ex.scenarios for seed in (1, 7)]


def run(exercise: Exercise, scenario: Scenario, seed: int):
    sim = exercise.simulation(exercise.reference.program(), scenario, seed=seed)
    sim.run()
    return sim.trace


@pytest.mark.parametrize(
    ("exercise", "scenario", "seed"), CASES, ids=[f"{e.number}-{s}-{seed}" for e, s, seed in CASES]
)
def test_every_scenario_stays_inside_the_conditions_the_task_states_or_says_it_leaves_them(exercise, scenario, seed):
    chosen = exercise.scenario(scenario)
    assert not undeclared_breaks(exercise.conditions, chosen, run(exercise, chosen, seed))


def test_the_course_states_its_conditions_where_its_tasks_do():
    """The tasks that say how many objects the operator loads, or how far apart, have the condition."""
    stated = {ex.number: [c.words for c in ex.conditions] for ex in WITH_CONDITIONS}
    for number in ("4.3.5", "4.3.7", "4.3.8", "4.3.10", "4.3.17", "6.3.1", "6.3.2", "6.3.3", "6.3.4", "6.3.5"):
        assert stated.get(number), number


@pytest.mark.parametrize("exercise", EXERCISES, ids=[ex.number for ex in EXERCISES])
def test_every_fault_a_scenario_injects_is_one_the_task_speaks_of(exercise):
    assert not [p for s in exercise.scenarios for p in fault_problems(s)]


def test_a_fault_the_task_does_not_speak_of_is_reported_and_words_it_does_not_have_do_not_load():
    ex = get("4.3.5")
    dead = Scenario("S2 dead", stuck("S2", False, t="0s"), place("p1", at="S1", t="0.5s"), duration="4s")
    (problem,) = fault_problems(dead)
    assert "injects a fault (stick S2 at False at 0 ns" in problem
    words = Scenario(
        "S2 dead", stuck("S2", False, t="0s"), duration="4s", outside={FAULTS: "the belt stops when S2 fails"}
    )
    assert not fault_problems(words)
    with pytest.raises(ExerciseError, match="which the task text does not state"):
        rebuilt(ex, scenarios=[*ex.scenarios, words])


def test_a_condition_quotes_the_task_and_a_declaration_names_a_condition():
    ex = get("4.3.5")
    with pytest.raises(ExerciseError, match="is not in the task text"):
        rebuilt(ex, conditions=[assumes("The operator loads two objects at most", parts_at_once(2))])
    typo = Scenario(
        "typo", place("p1", at="S1", t="0.5s"), duration="4s", outside={"Only one object at a time": ex.task[:20]}
    )
    with pytest.raises(ExerciseError, match="not a condition of the exercise"):
        rebuilt(ex, scenarios=[*ex.scenarios, typo])


def test_4_3_5_a_second_object_while_one_waits_at_s2_leaves_the_task_s_one_object_at_a_time():
    """The case issue 27 found: 'new object while one waits at S2' graded what the task rules out ("Only one object
    is on the conveyor at a time"). Put back, it is reported; declared with words the task does not have, it does
    not load."""
    ex = get("4.3.5")
    second = Scenario(
        "new object while one waits at S2",
        place("p1", at="S1", t="0.5s"),
        place("p2", at="S1", when=held("S2", "0.5s")),
        remove("p1", when=held("S2", "1s")),
        duration="8s",
    )
    (problem,) = undeclared_breaks(ex.conditions, second, run(ex, second, 1))
    assert "Only one object is on the conveyor at a time" in problem and "at most 1" in problem
    declared = Scenario(*[second.name, *second.actions], duration="8s", outside={ex.conditions[0].words: ex.task[:9]})
    assert not undeclared_breaks(ex.conditions, declared, run(ex, declared, 1))


def test_4_3_10_a_second_object_loaded_on_d1_leaves_one_object_per_conveyor():
    """4.3.10's condition counts each conveyor: a second object on D1 while the first is still on it leaves it, and
    the report names the conveyor."""
    ex = get("4.3.10")
    second = Scenario(
        "second object on D1",
        place("p1", at="D1_OS1", t="0.3s"),
        place("p2", at="D1_OS1", when=after_event("part entered", "D1_OS2"), delay="0.2s"),
        duration="6s",
    )
    (problem,) = undeclared_breaks(ex.conditions, second, run(ex, second, 1))
    assert "Consider one object per conveyor" in problem and "(objects on D1) <= 1" in problem


def test_a_declaration_the_run_does_not_need_is_reported():
    ex = get("4.3.5")
    one = ex.scenario("three objects")
    declared = Scenario(one.name, *one.actions, duration="25s", outside={ex.conditions[0].words: "x"})
    (problem,) = undeclared_breaks(ex.conditions, declared, run(ex, declared, 1))
    assert "but the run kept it" in problem


def rebuilt(ex: Exercise, **changes) -> Exercise:
    fields = dict(
        number=ex.number,
        slug=ex.slug,
        title=ex.title,
        task=ex.task,
        io=ex.io,
        rig=ex.rig,
        scenarios=ex.scenarios,
        checks=[gc.check for gc in ex.checks],
        solutions=ex.solutions,
        requirements=ex.requirements,
        conditions=ex.conditions,
    )
    return Exercise(**{**fields, **changes})
