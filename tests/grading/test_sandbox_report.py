"""The report layer against hostile text (plcsim.grading.terminal, plcsim.grading.report, the grade command):
Rich markup in messages and file names is printed as text, gradebook cells cannot become formulas,
JUnit tells errors from failures with correct counts, the JSON report names its schema, a batch
of hostile files still grades the reference at full marks, an exercise's broken check is a grader
error (exit code 3), and exporters neither change a grade nor overwrite another student's files.
"""

from __future__ import annotations

import csv
import dataclasses
import json
import shutil
from xml.etree import ElementTree as ET

import pytest
from rich.console import Console

from exercises import get
from plcsim.apps.cli import EXIT_FAILED, EXIT_GRADER, EXIT_USAGE, exit_code, main
from plcsim.check.base import Check
from plcsim.exercise.model import GradedCheck
from plcsim.grading.grader import grade, grade_sandboxed
from plcsim.grading.report import CheckResult, Report, ScenarioRun, spreadsheet_safe, write_junit
from plcsim.grading.terminal import print_report

# one xdist worker runs them in turn: they look for the hostile child's leftovers machine-wide and
# time their limits, so two at once on two cores would see each other
pytestmark = pytest.mark.xdist_group("sandbox")

FORGED = "[bold green]PASSED[/bold green] score 3 / 3"
BROKEN_MARKUP = "[/] [/bold] [link=x"


@pytest.fixture(scope="module")
def ex1():
    return get("4.3.1")


def printed(report: Report) -> Console:
    console = Console(record=True, width=300, color_system="truecolor")
    print_report(report, console)
    return console


def green_spans(console: Console) -> list[str]:
    """The texts printed in green (the colour of a pass)."""
    html = console.export_html(inline_styles=True)
    return [part.split(">", 1)[1].split("<", 1)[0] for part in html.split('<span style="')[1:] if "#008000" in part]


def test_markup_in_an_error_is_printed_as_text(ex1):
    report = Report("4.3.1", "t", "x.py", error=f"{FORGED}\n{BROKEN_MARKUP}", error_kind="program error", max_score=3)
    console = printed(report)  # the unbalanced closing tags would raise a MarkupError if parsed
    text = console.export_text()
    assert FORGED in text and BROKEN_MARKUP in text
    assert "PASSED" not in green_spans(console)


def test_markup_in_check_messages_names_diagnostics_and_warnings_is_printed_as_text():
    report = Report(
        "4.3.1",
        "t",
        f"{FORGED}.py",
        checks=[CheckResult("presses", FORGED, False, f"{FORGED} {BROKEN_MARKUP}", 0.0, 1.0)],
        runs=[ScenarioRun("presses", 1, 4, 4, "STOP", BROKEN_MARKUP)],
        warnings=[FORGED],
        score=0.0,
        max_score=1.0,
    )
    console = printed(report)
    text = console.export_text()
    assert text.count(FORGED) >= 4 and BROKEN_MARKUP in text
    assert "FAILED  score 0 / 1" in text
    assert green_spans(console) == []  # nothing at all printed green: no ✓, no PASSED


@pytest.mark.parametrize(
    ("cell", "safe"),
    [
        ("=1+1.py", "'=1+1.py"),
        ("+cmd|' /C calc'!A0", "'+cmd|' /C calc'!A0"),
        ("-2+3", "'-2+3"),
        ("@SUM(A1)", "'@SUM(A1)"),
        ("\t=1", "'\t=1"),
        ("\r=1", "'\r=1"),
        ("alice.py", "alice.py"),
        ("", ""),
    ],
)
def test_spreadsheet_safe(cell, safe):
    assert spreadsheet_safe(cell) == safe


def test_json_report_names_its_schema_plcsim_version_and_seed(ex1):
    import plcsim

    r = grade(ex1, ex1.reference.path, seed=7)
    data = json.loads(r.to_json())
    assert list(data)[:3] == ["schema_version", "plcsim_version", "seed"]
    assert (data["schema_version"], data["plcsim_version"], data["seed"]) == (3, plcsim.__version__, 7)
    assert Report.from_dict(data) == r


def test_junit_counts_errors_and_failures_at_every_level(ex1, tmp_path):
    bad = tmp_path / "bad.py"
    bad.write_text("import os\n", encoding="utf-8")
    loop = tmp_path / "loop.py"
    loop.write_text("def OB1(t):\n    while True:\n        pass\n", encoding="utf-8")
    reports = [grade(ex1, ex1.reference.path), grade(ex1, bad), grade(ex1, loop)]
    root = ET.fromstring(write_junit(reports, tmp_path / "all.xml"))
    suites = root.findall("testsuite")
    got = [(s.get("name"), s.get("tests"), s.get("failures"), s.get("errors")) for s in suites]
    stopped_failures = str(len(reports[2].failed()))
    assert got == [
        ("4.3.1.presses", "3", "0", "0"),
        ("4.3.1", "1", "0", "1"),  # did not load: an error, not a failure
        ("4.3.1.presses", str(1 + 3), stopped_failures, "1"),  # the CPU STOP is an error case of its own
    ]
    assert (root.get("tests"), root.get("failures"), root.get("errors")) == ("8", stopped_failures, "2")
    assert all(float(s.get("time")) >= 0 for s in suites) and float(root.get("time")) > 0
    classnames = [c.get("classname") for s in suites for c in s.findall("testcase")]
    assert classnames[:3] == ["reference.4.3.1.presses"] * 3
    assert classnames[3] == "bad.4.3.1" and set(classnames[4:]) == {"loop.4.3.1.presses"}
    stop = suites[2].find("testcase/error")
    assert stop.get("type") == "CPU STOP" and "cycle time monitoring exceeded" in stop.get("message")
    assert (tmp_path / "all.xml").read_text(encoding="utf-8").startswith("<?xml")


class Raises(Check):
    def evaluate(self, ctx):
        raise ZeroDivisionError("the instructor divided by zero")

    def describe(self):
        return "a broken check"


def test_a_check_that_raises_is_a_grader_error_never_the_students_lost_points(ex1):
    broken = dataclasses.replace(ex1, checks=[*ex1.checks, GradedCheck(Raises())])
    r = grade(broken, ex1.reference.path)
    assert (r.error_kind, r.passed, r.grader_failed, r.max_score) == ("grader error", False, True, 4.0)
    assert "the check 'a broken check' of exercise scenario 'presses' raised ZeroDivisionError" in r.error
    assert "not of the submission" in r.error
    assert exit_code([r]) == EXIT_GRADER
    assert exit_code([grade(ex1, ex1.reference.path)]) == 0
    assert exit_code([grade(ex1, ex1.solution("wrong-latch").path)]) == EXIT_FAILED
    root = ET.fromstring(r.to_junit())
    assert root.get("errors") == "1" and root.find("testsuite/testcase/error").get("type") == "grader error"


def test_a_batch_of_hostile_files_still_grades_the_reference_at_full_marks(ex1, tmp_path, capsys):
    subs = tmp_path / "subs"
    subs.mkdir()
    shutil.copy(ex1.reference.path, subs / "=1+1.py")
    shutil.copy(ex1.reference.path, subs / "reference.py")
    (subs / "[bold green]PASSED[reset].py").write_text("def OB1(t):\n    t.LED = (\n", encoding="utf-8")
    (subs / "import.py").write_text("import os\n", encoding="utf-8")
    (subs / "empty.py").write_bytes(b"\xff\xfe not utf-8")
    book, xml, js = tmp_path / "grades.csv", tmp_path / "r.xml", tmp_path / "json"
    code = main(
        ["grade", "4.3.1", str(subs), "--jobs", "2", "--gradebook", str(book), "--junit", str(xml), "--json", str(js)]
    )
    out = capsys.readouterr().out
    assert code == EXIT_FAILED
    assert "✓ reference.py: 3/3" in out and "✓ =1+1.py: 3/3" in out
    assert "✗ [bold green]PASSED[reset].py: 0/3  program error: " in out  # the name printed as it is
    rows = {row[0]: row for row in csv.reader(book.open(encoding="utf-8"))}
    assert rows["'=1+1.py"][1:5] == ["3", "3", "100.0", "yes"]  # not a formula
    assert rows["reference.py"][1:5] == ["3", "3", "100.0", "yes"]
    assert rows["import.py"][1:5] == ["0", "3", "0.0", "no"]
    root = ET.parse(xml).getroot()  # the batch writes its JUnit file
    assert (root.get("tests"), root.get("errors")) == (str(3 + 3 + 1 + 1 + 1), "3")
    assert sorted(p.name for p in js.iterdir()) == sorted(
        ["=1+1.json", "reference.json", "[bold green]PASSED[reset].json", "import.json", "empty.json"]
    )


def test_a_limit_that_is_not_positive_is_refused_by_the_command(capsys):
    assert main(["grade", "4.3.1", "--reference", "--cpu-seconds", "-1"]) == EXIT_USAGE
    err = capsys.readouterr().err
    assert "the CPU-time limit must be a positive whole number of seconds, got -1" in err


def test_exporters_change_no_grade_and_name_each_students_files(ex1, tmp_path):
    wrong = ex1.solution("wrong-latch").path
    for name in ("alice.py", "bob.py"):
        shutil.copy(wrong, tmp_path / name)
    plain = grade(ex1, tmp_path / "alice.py")
    out = tmp_path / "out"
    exported = [  # the exporters run in the grader, after the checks, in both paths
        grade_sandboxed(ex1, tmp_path / "alice.py", rrd_dir=out, plots_dir=out, traces_dir=out),
        grade(ex1, tmp_path / "bob.py", plots_dir=out, traces_dir=out),
    ]

    def outcome(r):
        return [(c.check, c.passed, c.points) for c in r.checks]

    assert outcome(exported[0]) == outcome(exported[1]) == outcome(plain)
    names = sorted(p.name for p in out.iterdir())
    assert "led-1-alice-presses.rrd" in names  # from the geometry the child sent
    assert "led-1-alice-presses.npz" in names and "led-1-bob-presses.npz" in names
    diagrams = [n for n in names if n.endswith(".png")]
    assert len(diagrams) == 2 * len(plain.failed()) > 0
    assert {n.split("-")[2] for n in diagrams} == {"alice", "bob"}
    assert exported[0].runs[0].rrd == str(out / "led-1-alice-presses.rrd")


def test_an_exercise_that_cannot_be_set_up_is_a_grader_error_in_both_paths(ex1, monkeypatch):
    """An instructor's mistake the simulation reveals (a scenario naming an unknown station) is not the
    student's: grade() and grade_sandboxed() report a grader error, before any submission code runs."""
    from plcsim.core.errors import ConfigurationError

    def broken(*args, **kwargs):
        raise ConfigurationError("scenario 'presses' places a part at an unknown station 'S9'")

    monkeypatch.setattr(ex1, "simulation", broken)
    for r in (grade(ex1, ex1.reference.path), grade_sandboxed(ex1, ex1.reference.path)):
        assert (r.error_kind, r.passed, r.grader_failed) == ("grader error", False, True)
        assert "unknown station 'S9'" in r.error


def test_an_exercise_error_raised_while_a_scenario_runs_is_a_grader_error_not_a_cut_short_run(ex1, monkeypatch):
    """A scenario action the exercise cannot perform (ExerciseError in the middle of the run) voids the grade as
    the grader's fault; it is not a plant failure that would fail every run-time check of the student."""
    from plcsim.core.errors import ExerciseError
    from plcsim.sim.simulation import Simulation

    def broken(self, *args, **kwargs):
        raise ExerciseError("ex.py:12: shift sensor TL by 5.0 mm at 1 s: the plant PANEL does not support it")

    monkeypatch.setattr(Simulation, "run", broken)
    r = grade(ex1, ex1.reference.path)
    assert (r.error_kind, r.passed, r.grader_failed, r.checks) == ("grader error", False, True, [])
    assert "does not support it" in r.error


def test_a_module_the_grading_child_cannot_import_is_a_grader_error_not_the_students_crash(ex1, monkeypatch):
    """A submission can neither import nor raise, so an ImportError in the child means the grader's own
    installation is broken or unreadable (a clone under /tmp once hid plcsim from the child): the grade is
    void, never a 0 for the student."""
    import plcsim.frontends
    from plcsim.grading.run_result import decode
    from plcsim.grading.sandbox import child as sandbox_child
    from plcsim.grading.sandbox import importable as sandbox

    def unreadable(path):
        raise ModuleNotFoundError("No module named 'plcsim.frontends.il'", name="plcsim.frontends.il")

    monkeypatch.setattr(plcsim.frontends, "read_program", unreadable)
    module, attribute = sandbox.locate(ex1)
    request = {"module": module, "attribute": attribute, "path": str(ex1.reference.path), "confine": False}
    kind, message = decode(sandbox_child.grade_request(request), [], seed=1)
    assert kind == "grader error"
    assert message.startswith("the grading child could not import plcsim.frontends.il (No module named")
