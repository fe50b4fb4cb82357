"""Instructors' own exercises, found by path (``plcsim grade my_course/lamp.py alice.py``, ``plcsim list
--exercises my_course/``), with the registry's validation and broken-module reporting; a handout without the
solutions; ``plcsim run`` never runs a reference unless asked to."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from exercises import get, load_path
from plcsim.apps.cli import EXIT_USAGE, main
from plcsim.core.errors import ConfigurationError, ExerciseError

LAMP = '''"""A lamp that follows its button (an instructor's exercise, outside the package)."""

from pathlib import Path

from plants import Panel
from plcsim.check import always, same
from plcsim.exercise.model import IO, Exercise, Solution
from plcsim.scenario.planning import Scenario
from plcsim.scenario.verbs import press

HERE = Path(__file__).parent
SOLUTIONS = [Solution("reference", HERE / "solutions" / "{slug}.py", explanation="LED := button")]

EXERCISE = Exercise(
    number="{number}",
    slug="{slug}",
    title="Lamp test",
    task="The LED follows the button.",
    io=[IO("TLACIDLO", "button", "Bool", "%I0.0", "NO"), IO("LED", "lamp", "Bool", "%Q0.0")],
    rig=lambda: Panel(buttons=("TLACIDLO",), switches=(), lamps=("LED",)),
    scenarios=[Scenario("press", press("TLACIDLO", t="0.5s", hold="0.3s"), duration="2s")],
    checks=[always(same("LED", "TLACIDLO")).named("LED follows the button")],
    solutions=[s for s in SOLUTIONS if s.path.is_file()],
)
'''
FOLLOW = "def OB1(t):\n    t.LED = t.TLACIDLO\n"


def course(tmp_path: Path, *names: str, solutions: bool = True) -> Path:
    folder = tmp_path / "my_course"
    (folder / "solutions").mkdir(parents=True)
    for k, name in enumerate(names):
        slug = f"lamp-{name}"
        (folder / f"{name}.py").write_text(LAMP.format(number=f"9.8.{k + 1}", slug=slug), encoding="utf-8")
        if solutions:
            (folder / "solutions" / f"{slug}.py").write_text(FOLLOW, encoding="utf-8")
    return folder


def submission(tmp_path: Path, source: str = FOLLOW) -> Path:
    folder = tmp_path / "submissions"
    folder.mkdir(exist_ok=True)
    path = folder / "alice.py"
    path.write_text(source, encoding="utf-8")
    return path


def test_an_exercise_file_is_found_by_path(tmp_path):
    folder = course(tmp_path, "lamp_a")
    exercise = get(str(folder / "lamp_a.py"))
    assert (exercise.number, exercise.slug, [s.name for s in exercise.solutions]) == (
        "9.8.1",
        "lamp-lamp_a",
        ["reference"],
    )


def test_a_folder_lists_what_loads_and_names_what_does_not(tmp_path):
    folder = course(tmp_path, "lamp_b", "lamp_c")
    (folder / "_helpers.py").write_text("X = 1\n", encoding="utf-8")  # a helper, not an exercise
    (folder / "typo.py").write_text(
        LAMP.format(number="9.8.9", slug="typo").replace('same("LED"', 'same("LDE"'), encoding="utf-8"
    )
    (folder / "broken.py").write_text("EXERCISE = (\n", encoding="utf-8")
    loaded, broken = load_path(folder)
    assert [e.number for e in loaded] == ["9.8.1", "9.8.2"]
    assert sorted(Path(b.file).name for b in broken) == ["broken.py", "typo.py"]
    assert "'LDE'" in str(next(b for b in broken if b.file.endswith("typo.py")))  # validated when loaded
    syntax = next(b for b in broken if b.file.endswith("broken.py"))
    assert str(syntax).startswith(f"{folder / 'broken.py'}:1: SyntaxError")
    with pytest.raises(ExerciseError, match=r"broken\.py:1: SyntaxError"):
        get(str(folder))  # a broken module is named, even where the others load
    (folder / "broken.py").unlink()
    (folder / "typo.py").unlink()
    with pytest.raises(ConfigurationError, match="holds 2 exercises"):
        get(str(folder))


def test_names_that_would_shadow_a_package_or_are_no_exercise_are_refused(tmp_path):
    folder = tmp_path / "course"
    folder.mkdir()
    (folder / "plants.py").write_text(LAMP.format(number="9.8.1", slug="x"), encoding="utf-8")
    with pytest.raises(ConfigurationError, match=r"'plants' is already taken by .*rename the file"):
        load_path(folder / "plants.py")
    (folder / "notes.txt").write_text("", encoding="utf-8")
    with pytest.raises(ConfigurationError, match="an exercise is a Python file"):
        load_path(folder / "notes.txt")
    with pytest.raises(ConfigurationError, match="no exercise file or folder"):
        get(str(folder / "missing.py"))
    (folder / "empty.py").write_text("X = 1\n", encoding="utf-8")
    with pytest.raises(ExerciseError, match="defines no EXERCISE"):
        get(str(folder / "empty.py"))


def test_the_command_grades_lists_and_shows_by_path(tmp_path, capsys):
    folder = course(tmp_path, "lamp_d")
    alice = submission(tmp_path)
    report = tmp_path / "out" / "alice.json"
    assert main(["grade", str(folder / "lamp_d.py"), str(alice), "--json", str(report)]) == 0  # in the sandbox
    data = json.loads(report.read_text(encoding="utf-8"))
    assert (data["exercise"], data["score"], data["max_score"], data["passed"]) == ("9.8.1", 1.0, 1.0, True)
    assert main(["list", "--exercises", str(folder)]) == 0
    assert "lamp-lamp_d" in capsys.readouterr().out
    assert main(["show", str(folder / "lamp_d.py"), "--solutions"]) == 0
    assert "Shipped programs" in capsys.readouterr().out
    assert main(["show", str(folder / "lamp_d.py"), "--no-solutions"]) == 0
    handout = capsys.readouterr().out
    assert "Shipped programs" not in handout and "LED := button" not in handout and "Lamp test" in handout


@pytest.fixture(autouse=True)
def wide_console(monkeypatch):
    monkeypatch.setenv("COLUMNS", "250")  # the messages are asserted whole, not as Rich wraps them


def test_a_broken_exercise_in_a_listed_folder_is_named_and_fails_the_command(tmp_path, capsys):
    folder = course(tmp_path, "lamp_e")
    (folder / "broken.py").write_text("EXERCISE = (\n", encoding="utf-8")
    assert main(["list", "--exercises", str(folder)]) == EXIT_USAGE
    captured = capsys.readouterr()
    assert "lamp-lamp_e" in captured.out and "broken.py:1: SyntaxError" in captured.err


def test_run_never_runs_the_reference_unless_asked(tmp_path, capsys):
    assert main(["run", "4.3.6"]) == EXIT_USAGE
    assert "which program? plcsim run 4.3.6 --program FILE.py" in capsys.readouterr().err
    handout = course(tmp_path, "lamp_f", solutions=False)  # what students get: no solutions folder content
    assert get(str(handout / "lamp_f.py")).solutions == []
    assert main(["run", str(handout / "lamp_f.py"), "--reference"]) == EXIT_USAGE
    assert "ships no reference solution; run yours with --program FILE.py" in capsys.readouterr().err
    assert main(["run", str(handout / "lamp_f.py"), "--program", str(submission(tmp_path))]) == 0
