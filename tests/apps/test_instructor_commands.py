"""The instructor's commands on an exercise of their own (docs/examples/reject_course): ``check-exercise`` grades its
shipped programs on several seeds and says which do not grade as the exercise says; ``draw`` pictures a rig; the hints
of ``show`` and ``run`` repeat the name that found a file-loaded exercise (issue 28, items 4, 5, 7)."""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest

from plcsim.apps.cli import EXIT_FAILED, main

COURSE = Path(__file__).resolve().parents[2] / "docs" / "examples" / "reject_course"


@pytest.fixture(autouse=True)
def wide_console(monkeypatch):
    monkeypatch.setenv("COLUMNS", "250")  # the lines are asserted whole, not as Rich wraps them


@pytest.fixture
def course(tmp_path, monkeypatch, request):
    """A copy of the example course in the working directory (paths short and relative); its exercise module has a
    name of its own per test (``reject_hints.py``: the others may be loaded in this process)."""
    copy = tmp_path / "reject_course"
    shutil.copytree(COURSE, copy, ignore=shutil.ignore_patterns("__pycache__"))
    (copy / "reject.py").rename(copy / f"reject_{request.node.name.split('_')[-1]}.py")
    monkeypatch.chdir(tmp_path)
    return copy


def test_check_exercise_passes_a_course_whose_programs_grade_as_it_says(capsys):
    assert main(["check-exercise", str(COURSE / "reject.py"), "--seeds", "2"]) == 0
    out = capsys.readouterr().out
    assert "exercise 9.7.1 Reject the bad parts: its programs on seeds 1, 2" in out
    assert "✓ reference [reference]: as it says" in out and "✓ no-piston [wrong]: as it says" in out
    assert "every program grades as the exercise says" in out


def test_check_exercise_names_the_programs_that_do_not_grade_as_it_says_failing(course, capsys):
    wrong = course / "solutions" / "piston_follows_b1.py"
    wrong.write_text((course / "solutions" / "reference.py").read_text(encoding="utf-8"), encoding="utf-8")
    exercise = course / "reject_failing.py"
    text = exercise.read_text(encoding="utf-8")
    unrestricted = 'event_data("part in bin", "bad", "reject").equals(1).named("only bad parts in the reject bin")'
    checked = f"only({unrestricted}, *WITH_BAD)"
    assert checked in text
    exercise.write_text(text.replace(checked, unrestricted), encoding="utf-8")  # in every scenario: "one good part"
    assert main(["check-exercise", "reject_course/reject_failing.py", "--seeds", "1"]) == EXIT_FAILED
    out = capsys.readouterr().out
    assert "✗ reference [reference]: 1 problem(s)" in out
    assert (
        "seed 1: one good part: only bad parts in the reject bin: failed: expected every bad of 'part in bin' reject "
        "= 1; there was nothing to measure; a correct program gave this check nothing to check in scenario 'one good "
        "part': if that scenario cannot show it, apply the check only where it can: only(check, 'one bad part', "
        "'three parts') in the exercise"
    ) in out
    assert "✗ piston-follows-B1 [wrong]: 1 problem(s)" in out
    assert "seed 1: should fail 'Y1 stays out 0.4 s' (Y1 := B1: the piston goes back" in out
    assert "it failed ['only bad parts in the reject bin']" in out


def test_draw_writes_the_picture_of_a_rig_or_an_exercise_s_rig(tmp_path, capsys):
    assert main(["draw", "SORT", "-o", str(tmp_path / "sort.png")]) == 0
    assert main(["draw", str(COURSE / "reject.py"), "-o", str(tmp_path / "out" / "reject.png")]) == 0
    for name in ("sort.png", "out/reject.png"):
        assert (tmp_path / name).read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert "drawing of REJECT" in capsys.readouterr().out


def test_the_hints_of_show_and_run_name_an_exercise_by_the_path_that_found_it_hints(course, capsys):
    assert main(["show", "reject_course/reject_hints.py", "--solutions"]) == 0  # the shipped programs: instructors
    assert "(grade one with: plcsim grade reject_course/reject_hints.py --solution NAME)" in capsys.readouterr().out
    program = str(course / "solutions" / "reference.py")
    assert main(["run", "reject_course/reject_hints.py", "--program", program]) == 0
    assert "(grade every scenario with: plcsim grade reject_course/reject_hints.py FILE.py)" in capsys.readouterr().out
    assert main(["grade", "reject_course/reject_hints.py", program, "--no-sandbox"]) == 0  # the hint's form works
