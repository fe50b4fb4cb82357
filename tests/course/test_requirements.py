"""Fair to the student: every check names the words of the task it grades (issue 27).

The exercise refuses to load when a check's words are not in its task (tests/exercise/test_exercise_validation.py);
here, every check of every shipped exercise names its words, so that ``plcsim show`` prints each requirement a
grade depends on, and what a student reads cites nothing they do not have and gives the numbers they need.
"""

from __future__ import annotations

import pytest

from exercises import all_exercises

EXERCISES = all_exercises()


@pytest.mark.parametrize("exercise", EXERCISES, ids=[ex.number for ex in EXERCISES])
def test_every_check_names_the_words_of_the_task_it_grades(exercise):
    task = " ".join(exercise.task.split()).lower()
    unnamed = [c.name for c in exercise.checks if not c.requirement]
    assert not unnamed, f"{exercise.number}: these checks name no words of the task: {unnamed}"
    for check in exercise.checks:
        assert " ".join(check.requirement.split()).lower() in task, check.name
    listed = [c.name for _words, checks in exercise.requirement_list() for c in checks]
    assert sorted(listed) == sorted(c.name for c in exercise.checks)


@pytest.mark.parametrize("exercise", EXERCISES, ids=[ex.number for ex in EXERCISES])
def test_what_a_student_reads_cites_no_section_of_a_document_they_do_not_have(exercise):
    texts = [exercise.task, *(s.description or "" for s in exercise.scenarios), *(c.name for c in exercise.checks)]
    assert not [t for t in texts if "§" in t or "spec" in t.lower()]


def test_the_colour_sorters_task_gives_every_colour_value_the_scenarios_use():
    """4.3.17 asks for colour intervals: the task states the plant's typical values, its noise, the ambient offset
    and the spread of worn objects the scenarios load, and the values of the objects of no colour."""
    from exercises.ex_4_3_17 import AMBIENT, BLACK, EDGE_RAW, STEEL
    from plants.components.colour_sensor import ColourSensor
    from plants.sort import COLOURS

    exercise = next(ex for ex in EXERCISES if ex.number == "4.3.17")
    task = exercise.task
    sensor = ColourSensor("FARBA", 0.0, 0.0, colours=COLOURS)
    numbers = [*COLOURS.values(), sensor.bare, sensor.noise, BLACK["colour_raw"], STEEL["colour_raw"]]
    for value in numbers:
        assert f"about {value:.0f}" in task, value
    spread = max(abs(raw - COLOURS[colour]) for colour, raw in EDGE_RAW)
    assert f"up to {spread:.0f} away from its colour's value" in task
    (ambient,) = [a for a in exercise.scenario(AMBIENT).actions if a.verb == "set_ambient"]
    assert f"daylight may add up to {ambient.args['offset']:.0f}" in task
    assert "raw units 0…27648" in task and "at least 3 s apart" in task
