"""The registry: exercises, rigs and front ends come from entry points, never from imports in plcsim.

An instructor's package registers an exercise with a ``*.dist-info/entry_points.txt`` on ``sys.path`` (what
``pip install`` writes), and ``plcsim list`` / ``plcsim grade`` find it. A student's ``exercises.py`` or
``plants.py`` in the working folder changes nothing.
"""

from __future__ import annotations

import ast
import importlib.metadata
import re
import subprocess
import sys
import textwrap
import tomllib
from pathlib import Path

import pytest
from platforms import UTF8, console_script, utf8_env

import plants
import plcsim.exercise.catalog
from plcsim.apps.cli import main
from plcsim.core import registry
from plcsim.core.errors import ConfigurationError, ProgramError
from plcsim.frontends import read_program, suffixes

ROOT = Path(__file__).resolve().parents[2]

EXERCISE = """
from plants import Panel
from plcsim.check import always, same
from plcsim.exercise.model import IO, Exercise
from plcsim.scenario.planning import Scenario
from plcsim.scenario.verbs import press

EXERCISE = Exercise(
    number="9.1.1",
    slug="my-led",
    title="My LED",
    task="The LED follows the button.",
    io=[IO("TL1", "button", "Bool", "%I0.0", "NO"), IO("LED1", "lamp", "Bool", "%Q0.0")],
    rig=lambda: Panel(buttons=("TL1",), switches=(), lamps=("LED1",)),
    scenarios=[Scenario("press", press("TL1", t="0.5s", hold="0.3s"), duration="2s")],
    checks=[always(same("LED1", "TL1")).named("LED1 follows TL1")],
    solutions=[],
)
"""


def _dist(tmp_path: Path, name: str, entry_points: str) -> Path:
    """An installed distribution as pip leaves it: a package folder and its .dist-info with entry points."""
    site = tmp_path / "site"
    info = site / f"{name}-1.0.dist-info"
    info.mkdir(parents=True)
    (info / "METADATA").write_text(f"Metadata-Version: 2.1\nName: {name}\nVersion: 1.0\n", encoding="utf-8")
    (info / "entry_points.txt").write_text(textwrap.dedent(entry_points), encoding="utf-8")
    return site


@pytest.fixture
def instructor_package(tmp_path, monkeypatch):
    """``my_course`` with one exercise, registered in the group plcsim.exercises by its own dist-info."""
    site = _dist(tmp_path, "my_course", "[plcsim.exercises]\nmy_course = my_course\n")
    package = site / "my_course"
    package.mkdir()
    (package / "__init__.py").write_text("", encoding="utf-8")
    (package / "led.py").write_text(EXERCISE, encoding="utf-8")
    (package / "_helpers.py").write_text("raise RuntimeError('a helper module is not an exercise')\n", encoding="utf-8")
    monkeypatch.syspath_prepend(str(site))
    plcsim.exercise.catalog._catalog.cache_clear()
    yield package
    plcsim.exercise.catalog._catalog.cache_clear()
    for name in [m for m in sys.modules if m == "my_course" or m.startswith("my_course.")]:
        del sys.modules[name]


def test_plcsim_imports_nothing_from_plants_or_exercises():
    offenders = []
    for path in sorted((ROOT / "plcsim").rglob("*.py")):
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            names = (
                [a.name for a in node.names]
                if isinstance(node, ast.Import)
                else [node.module or ""]
                if isinstance(node, ast.ImportFrom)
                else []
            )
            offenders += [
                f"{path.relative_to(ROOT)}:{node.lineno}" for n in names if n.split(".")[0] in ("plants", "exercises")
            ]
    assert offenders == []


def test_the_installed_entry_points_are_the_ones_pyproject_declares():
    declared = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))["project"]["entry-points"]
    installed: dict[str, dict[str, str]] = {}
    for ep in importlib.metadata.distribution("plcsim").entry_points:
        installed.setdefault(ep.group, {})[ep.name] = ep.value
    for group in (registry.EXERCISES, registry.RIGS):
        assert installed.get(group) == declared[group], f"{group}: the install is stale, run pip install -e ."


def test_the_course_registers_its_rigs_and_exercises():
    assert {"CONV1", "CONV2x2", "CONV3", "MACHINE", "PANEL"} <= set(registry.rig_names())
    assert registry.rig_names() == sorted(registry.rig_names())
    assert registry.rig("conv1") is plants.Conv1 and plants.RIGS["PANEL"] is plants.Panel
    assert [ep.value for ep in registry.entry_points(registry.EXERCISES)] == ["exercises"]
    numbers = [e.number for e in plcsim.exercise.catalog.all_exercises()]
    assert numbers[0] == "4.3.1" and "4.3.7" in numbers and plcsim.exercise.catalog.broken_exercises() == ()


def test_an_unknown_rig_names_the_registered_ones():
    rigs = re.escape(", ".join(registry.rig_names()))
    with pytest.raises(ConfigurationError, match=rf"^no rig 'CONV4'; did you mean 'CONV3'.*\? \(rigs: {rigs}\)$"):
        registry.rig("CONV4")


def test_the_cli_help_lists_the_registered_rigs(monkeypatch, capsys):
    real = registry.entry_points

    def with_extra(group):
        found = real(group)
        if group == registry.RIGS:
            found.append(importlib.metadata.EntryPoint("LIFT", "my_rigs:Lift", registry.RIGS))
        return found

    monkeypatch.setattr(registry, "entry_points", with_extra)
    with pytest.raises(SystemExit):
        main(["run", "--help"])
    help_text = " ".join(capsys.readouterr().out.split())
    assert f"or a rig ({', '.join(ep.name for ep in real(registry.RIGS))}, LIFT)" in help_text


def test_an_instructors_package_is_listed_and_graded(instructor_package, capsys, tmp_path):
    assert main(["list"]) == 0
    out = capsys.readouterr().out
    assert "9.1.1" in out and "my-led" in out and "4.3.1" in out
    exercise = plcsim.exercise.catalog.get("my-led")
    assert exercise.number == "9.1.1" and exercise.defined_at.startswith(str(instructor_package / "led.py"))
    right = tmp_path / "right.py"
    right.write_text("def OB1(t):\n    t.LED1 = t.TL1\n", encoding="utf-8")
    wrong = tmp_path / "wrong.py"
    wrong.write_text("def OB1(t):\n    t.LED1 = not t.TL1\n", encoding="utf-8")
    assert main(["grade", "9.1.1", str(right), "--no-sandbox"]) == 0
    assert main(["grade", "9.1.1", str(wrong), "--no-sandbox"]) == 1
    assert "LED1 follows TL1" in capsys.readouterr().out


def test_a_broken_entry_point_is_named_and_the_others_still_load(instructor_package, tmp_path, monkeypatch, capsys):
    site = _dist(tmp_path / "other", "broken_course", "[plcsim.exercises]\nbroken = no_such_course.sub\n")
    monkeypatch.syspath_prepend(str(site))
    plcsim.exercise.catalog._catalog.cache_clear()
    assert main(["list"]) == 2
    out, err = capsys.readouterr()
    assert "9.1.1" in out and "4.3.1" in out
    assert "plcsim.exercises entry point broken = 'no_such_course.sub' cannot be loaded" in " ".join(err.split())
    assert "ModuleNotFoundError" in err and "Traceback" not in err


def test_another_packages_front_end_reads_its_suffix(tmp_path, monkeypatch):
    site = _dist(tmp_path, "my_frontend", "[plcsim.frontends]\nlad = my_frontend:read_lad\n")
    (site / "my_frontend.py").write_text(
        "from plcsim.frontends.python.program import Program\n\n"
        "def read_lad(path):\n"
        "    a, b = path.read_text().split('->')\n"
        "    return Program.from_source(f'def OB1(t):\\n    t.{b.strip()} = t.{a.strip()}\\n', filename=str(path))\n",
        encoding="utf-8",
    )
    monkeypatch.syspath_prepend(str(site))
    program = tmp_path / "rung.lad"
    program.write_text("TL1 -> LED1", encoding="utf-8")
    assert ".lad" in suffixes() and ".py" in suffixes()
    assert [n.name for n in read_program(program).tasks["OB1"].networks] == ["OB1"]
    with pytest.raises(ProgramError, match=r"no front end reads \.xyz; use .*\.lad, .*\.py"):
        read_program(tmp_path / "rung.xyz")


SHADOWS = {
    "exercises.py": "raise SystemExit('the student exercises.py was imported')\n",
    "plants.py": "raise SystemExit('the student plants.py was imported')\n",
}


@pytest.mark.parametrize("how", ["script", "module"])
def test_a_students_files_in_the_working_folder_do_not_replace_the_course(tmp_path, how):
    for name, text in SHADOWS.items():
        (tmp_path / name).write_text(text, encoding="utf-8")
    program = tmp_path / "led.py"
    program.write_text("def OB1(t):\n    t.LED = t.TLACIDLO\n", encoding="utf-8")
    command = [str(console_script("plcsim"))] if how == "script" else [sys.executable, "-m", "plcsim"]
    env = {k: v for k, v in utf8_env().items() if k != "PYTHONPATH"}
    listed = subprocess.run([*command, "list"], cwd=tmp_path, capture_output=True, **UTF8, env=env, timeout=300)
    assert listed.returncode == 0, listed.stderr
    assert "4.3.1" in listed.stdout and "student" not in listed.stdout + listed.stderr
    graded = subprocess.run(
        [*command, "grade", "4.3.1", "led.py", "--no-sandbox"],
        cwd=tmp_path,
        capture_output=True,
        **UTF8,
        env=env,
        timeout=300,
    )
    assert "student" not in graded.stdout + graded.stderr
    assert graded.returncode == 0 and "score 3 / 3" in graded.stdout, graded.stdout


def test_in_a_session_whose_working_folder_is_on_the_path_the_installed_course_is_loaded(tmp_path):
    for name, text in SHADOWS.items():
        (tmp_path / name).write_text(text, encoding="utf-8")
    code = (
        "import sys; sys.path.insert(0, '')\n"
        "from plcsim.core import registry\nfrom plcsim.exercise import catalog\n"
        "print(catalog.get('4.3.1').number, registry.rig('PANEL').__name__)\n"
        "import exercises, plants; print(exercises.__file__ != 'exercises.py', plants.__file__)\n"
    )
    done = subprocess.run([sys.executable, "-c", code], cwd=tmp_path, capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr
    first, second = done.stdout.splitlines()
    assert first == "4.3.1 Panel"
    assert second.startswith("True ") and second.endswith(str(ROOT / "plants" / "__init__.py"))


def test_a_shadowing_module_the_session_imported_itself_is_named_by_its_file(tmp_path):
    (tmp_path / "exercises.py").write_text("EXERCISE = None\n", encoding="utf-8")
    code = (
        "import sys; sys.path.insert(0, ''); import exercises\nfrom plcsim.exercise import catalog\n"
        "catalog.get('4.3.1')\n"
    )
    done = subprocess.run([sys.executable, "-c", code], cwd=tmp_path, capture_output=True, text=True, timeout=300)
    assert done.returncode != 0
    message = " ".join(done.stderr.split())
    assert "no exercise '4.3.1'" in message
    assert f"(not loaded: {tmp_path / 'exercises.py'}:1: the module defines no EXERCISE = Exercise(...))" in message


def test_run_of_neither_an_exercise_nor_a_rig_names_the_rigs(tmp_path, capsys):
    program = tmp_path / "p.py"
    program.write_text("def OB1(t):\n    pass\n", encoding="utf-8")
    assert main(["run", "PANELX", "--program", str(program)]) == 2
    err = " ".join(capsys.readouterr().err.split())
    assert "no exercise 'PANELX'" in err
    assert f"the rigs are {', '.join(registry.rig_names())}; did you mean 'PANEL'?" in err
