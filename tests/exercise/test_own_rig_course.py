"""The worked example of docs/writing-a-rig.md, an instructor's own rig and exercise outside the package
(docs/examples/reject_course): its reference passes on several seeds, each wrong solution fails where its ``fails=``
says; parts drawn with ``one_of`` vary with the seed; bins report the property the rig declares; a check that a
scenario cannot apply fails the reference with the fix in its message (issue 28)."""

from __future__ import annotations

import dataclasses
from pathlib import Path

import pytest

from exercises import get
from plcsim.check import event_data
from plcsim.exercise import Exercise
from plcsim.grading.grader import grade

COURSE = Path(__file__).resolve().parents[2] / "docs" / "examples" / "reject_course"


@pytest.fixture(scope="module")
def reject():
    return get(str(COURSE / "reject.py"))


@pytest.mark.parametrize("seed", [1, 7])
def test_the_shipped_programs_grade_as_their_fails_say(reject, seed):
    for solution in reject.solutions:
        report = grade(reject, solution.path, seed=seed)
        failed = {c.check for c in report.failed()}
        if solution.kind == "reference":
            assert report.passed and report.score == report.max_score == 11.0, failed
        else:
            assert set(solution.fails) <= failed and not report.passed, (solution.name, failed)


def test_a_property_drawn_with_one_of_varies_with_the_seed_and_the_bins_report_it(reject):
    drawn, landed = set(), set()
    for seed in range(1, 9):
        sim = reject.simulation(reject.reference.program(), "three parts", seed=seed)
        sim.run(sim.scenario.duration_ns)
        events = sim.trace.events_of("part placed", None, "plant")
        drawn.add(tuple(e.data["bad"] for e in events))
        landed |= {(e.subject, e.data["bad"]) for e in sim.trace.events_of("part in bin", None, "plant")}
    assert drawn == {(True, False, True), (True, False, False)}  # p3 = one_of(True, False)
    assert landed == {("reject", True), ("good", False)}


def test_a_check_a_scenario_cannot_apply_fails_the_reference_naming_only(reject):
    unrestricted = event_data("part in bin", "bad", "reject").equals(1).named("only bad parts in the reject bin")
    checks = [c for c in reject.checks if c.name != unrestricted.title] + [unrestricted]
    exercise = Exercise(**{**_fields(reject), "checks": checks})
    report = grade(exercise, reject.reference.path, seed=1)
    failure = report.result("only bad parts in the reject bin")
    assert failure.scenario == "one good part" and not failure.passed
    assert failure.message == (
        "expected every bad of 'part in bin' reject = 1; there was nothing to measure; a correct program gave this "
        "check nothing to check in scenario 'one good part': if that scenario cannot show it, apply the check only "
        "where it can: only(check, 'one bad part', 'three parts') in the exercise"
    )


def test_a_student_program_gets_no_instructor_hint(reject, tmp_path):
    unrestricted = event_data("part in bin", "bad", "reject").equals(1).named("only bad parts in the reject bin")
    checks = [c for c in reject.checks if c.name != unrestricted.title] + [unrestricted]
    exercise = Exercise(**{**_fields(reject), "checks": checks})
    alice = tmp_path / "alice.py"
    alice.write_text(reject.reference.path.read_text(encoding="utf-8"), encoding="utf-8")
    message = grade(exercise, alice, seed=1).result("only bad parts in the reject bin").message
    assert message == "expected every bad of 'part in bin' reject = 1; there was nothing to measure"


def _fields(exercise: Exercise) -> dict:
    return {f.name: getattr(exercise, f.name) for f in dataclasses.fields(exercise) if f.init}
