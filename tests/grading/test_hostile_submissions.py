"""Submissions that attack the grader through its own messages and start-up, not through the sandbox: a
program error of megabytes, a file in no encoding a front end reads, a submission named like a module
the grader imports. Each is reported as the student's error, named, never as an invalid result or a crash."""

from __future__ import annotations

import re

import pytest
from platforms import UTF8, utf8_env

from exercises import get
from plcsim.grading.grader import grade, grade_sandboxed
from plcsim.grading.run_result import MAX_TEXT

pytestmark = pytest.mark.xdist_group("sandbox")

HUGE_LABEL = "A" * 3_000_000
JUMPS_TO_NOWHERE = f'@label({HUGE_LABEL!r})\ndef n1(t):\n    JMP("nowhere")\n\n\nOB1 = [n1]\n'


@pytest.fixture(scope="module")
def ex1():
    return get("4.3.1")


def test_a_program_error_of_3_mb_arrives_cut_and_named_not_as_an_invalid_result(ex1, tmp_path):
    path = tmp_path / "huge.py"
    path.write_text(JUMPS_TO_NOWHERE, encoding="utf-8")
    report = grade_sandboxed(ex1, path)
    assert report.error_kind == "program error"
    assert report.error.startswith(f"{path}, line 3: JMP to 'nowhere'")
    assert len(report.error) <= MAX_TEXT and report.error.endswith("more characters cut]")


@pytest.mark.parametrize("sandboxed", [False, True])
def test_an_il_file_neither_utf8_nor_cp1250_is_named_not_a_crash(ex1, tmp_path, sandboxed):
    path = tmp_path / "lab.il"
    path.write_bytes(b"LD X0.0\nWR Y0.0 ; \x81\x98\n")  # 0x81 and 0x98 are in neither
    report = (grade_sandboxed if sandboxed else grade)(ex1, path)
    assert (report.error_kind, report.error) == (
        "program error",
        f"{path}, line 2: this file is not text in UTF-8 or cp1250 (byte 0x81 in column 11); save it as UTF-8",
    )


def shadowing_numpy(folder, marker) -> str:
    """A submission saved as ``numpy.py``: imported instead of numpy, it leaves ``marker`` and fails."""
    return (
        f"import pathlib\npathlib.Path({str(marker)!r}).write_text('imported')\n"
        f"raise SystemExit('the submissions folder was imported from: {folder}')\n"
    )


def test_python_m_plcsim_in_the_submissions_folder_imports_no_submission(ex1, tmp_path):
    """``cd submissions && python -m plcsim grade ...``: ``-m`` puts the current folder first on sys.path; the
    grader and its children import nothing from it (the submission saved as numpy.py is graded, not run)."""
    import subprocess
    import sys
    from pathlib import Path

    subs, marker = tmp_path / "subs", tmp_path / "imported"
    subs.mkdir()
    (subs / "numpy.py").write_text(shadowing_numpy(subs, marker), encoding="utf-8")
    (subs / "ok.py").write_bytes(ex1.reference.path.read_bytes())
    root = Path(__file__).resolve().parents[2]  # this checkout's plcsim, exercises and plants
    env = utf8_env(PYTHONPATH=str(root))  # the marks ✓ and ✗, also where the console's code page lacks them
    done = subprocess.run(
        [sys.executable, "-m", "plcsim", "grade", "4.3.1", ".", "--jobs", "2"],
        cwd=subs,
        env=env,
        capture_output=True,
        **UTF8,
        timeout=300,
    )
    assert not marker.exists(), done.stderr[-2000:]
    assert "✓ ok.py: 3/3" in done.stdout, done.stdout + done.stderr[-2000:]
    assert "✗ numpy.py: 0/3  subset violation" in done.stdout
    assert done.returncode == 1


def test_a_grading_child_never_imports_from_the_submissions_folder(ex1, tmp_path, monkeypatch):
    """A notebook in the submissions folder: the folder is the current one and on sys.path; the child's
    path holds neither."""
    subs, marker = tmp_path / "subs", tmp_path / "imported"
    subs.mkdir()
    (subs / "numpy.py").write_text(shadowing_numpy(subs, marker), encoding="utf-8")
    (subs / "ok.py").write_bytes(ex1.reference.path.read_bytes())
    monkeypatch.chdir(subs)
    monkeypatch.syspath_prepend(str(subs))
    monkeypatch.setattr("sys.path", ["", *__import__("sys").path])
    report = grade_sandboxed(ex1, "ok.py")
    assert (report.error_kind, report.score) == (None, 3.0), report.error
    assert not marker.exists()


TOGGLES_EVERY_SCAN = "def OB1(t):\n    n = 0\n    while n < 10000:\n        n += 1\n        t.LED = not t.LED\n"
"""About 1 ms a scan: the whole of 4.3.1 costs a few seconds of CPU, within the default limit."""
TOGGLES_FAR_TOO_OFTEN = TOGGLES_EVERY_SCAN.replace("10000", "300000")
"""30 times the work a scan (under the cycle watchdog's million iterations): over a 3 s budget on any
machine, however fast (10 000 toggles ran the whole exercise under 3 s on one CI machine)."""


def test_a_submission_over_the_exercises_budget_is_too_slow_in_every_report_format(ex1, tmp_path, monkeypatch):
    """The budget is fitted to the reference (measured once per batch); over it is "too slow", told apart
    from a time limit and a crash in the terminal, JSON, JUnit, the gradebook and Gradescope."""
    import csv
    import io
    import json
    from pathlib import Path
    from xml.etree import ElementTree as ET

    import jsonschema
    from rich.console import Console

    from plcsim.grading.batch import grade_batch
    from plcsim.grading.report import gradescope_results, write_gradebook, write_junit
    from plcsim.grading.sandbox import limits
    from plcsim.grading.terminal import print_report

    monkeypatch.setattr(limits, "FLOOR_S", 3)  # the 4.3.1 reference costs far less than a second
    subs = tmp_path / "subs"
    subs.mkdir()
    (subs / "ok.py").write_bytes(ex1.reference.path.read_bytes())
    (subs / "slow.py").write_text(TOGGLES_FAR_TOO_OFTEN, encoding="utf-8")
    ok, slow = grade_batch(ex1, [subs / "ok.py", subs / "slow.py"])
    assert (ok.error_kind, ok.score) == (None, 3.0)
    assert slow.error_kind == "too slow"
    assert slow.error.startswith("too slow for this exercise: it used more than ")
    fitted = r"(× the reference's CPU time|the budget fitted to the reference)"  # the latter: it measured 0.00 s
    assert re.search(fitted + r" \(the reference \d+\.\d\d s, the budget \d+ s\)$", slow.error)
    buffer = io.StringIO()
    print_report(slow, Console(file=buffer, width=200, color_system=None))
    assert "too slow: 4.3.1" in buffer.getvalue()
    data = json.loads(slow.to_json())
    assert data["error_kind"] == "too slow"
    schema = json.loads((Path(__file__).parents[2] / "docs" / "report.schema.json").read_text(encoding="utf-8"))
    jsonschema.validate(data, schema)  # the published schema knows the outcome
    assert ET.fromstring(write_junit([ok, slow])).find(".//error").get("type") == "too slow"
    rows = list(csv.reader(write_gradebook([ok, slow], tmp_path / "g.csv").open(encoding="utf-8")))
    assert rows[2][5].startswith("too slow: too slow for this exercise")
    assert [t["name"] for t in gradescope_results(slow)["tests"]] == ["too slow"]


def test_an_instructor_can_grade_a_batch_without_the_budget(ex1, tmp_path, monkeypatch, capsys):
    """``--no-budget``: the same slow file is bounded by ``--cpu-seconds`` alone and gets its grade."""
    import json

    from plcsim.apps.cli import main
    from plcsim.grading.sandbox import limits

    monkeypatch.setattr(limits, "FLOOR_S", 3)
    subs = tmp_path / "subs"
    subs.mkdir()
    (subs / "slow.py").write_text(TOGGLES_EVERY_SCAN, encoding="utf-8")
    main(["grade", "4.3.1", str(subs), "--no-budget", "--json", str(tmp_path / "json")])
    capsys.readouterr()
    slow = json.loads((tmp_path / "json" / "slow.json").read_text(encoding="utf-8"))
    assert slow["error_kind"] != "too slow" and slow["max_score"] == 3.0, slow["error"]


def test_an_exercise_sets_its_own_budget(ex1, tmp_path):
    from dataclasses import replace

    from plcsim.grading.budget import fitted_limits
    from plcsim.grading.sandbox.limits import Budget, Limits

    assert fitted_limits(replace(ex1, cpu_budget_s=2.5), Limits(), seed=1).budget == Budget(3)
    fitted = fitted_limits(ex1, Limits(), seed=1)
    assert fitted.budget.cpu_seconds == 10 and 0 <= fitted.budget.reference_cpu_s < 1  # the floor binds
    assert (fitted.cpu_limit, Limits().cpu_limit) == (10, 60)


def test_a_reference_measured_at_0_s_is_measured_not_missing(ex1, monkeypatch):
    """Windows counts a thread's CPU time in ticks of about 16 ms: a quick reference reads 0.0 s there, and
    still gets the budget's floor (no budget at all would let a slow file run to the 60 s limit)."""
    from plcsim.grading import budget
    from plcsim.grading.sandbox.limits import Budget, Limits

    monkeypatch.setattr(budget.time, "thread_time", lambda: 12.5)  # a clock that has not ticked
    assert budget.reference_cpu_s(ex1, seed=1) == 0.0
    assert budget.fitted_limits(ex1, Limits(), seed=1).budget == Budget(10, 0.0)
    assert Budget(10, 0.0).too_slow() == (
        "too slow for this exercise: it used more than the budget fitted to the reference "
        "(the reference 0.00 s, the budget 10 s)"
    )


def test_a_two_million_line_il_file_is_too_slow_not_a_stalled_batch(tmp_path, monkeypatch):
    """The IL assembler is linear, and what it still costs is bounded by the exercise's budget."""
    from plcsim.grading.batch import grade_batch
    from plcsim.grading.sandbox import limits

    monkeypatch.setattr(limits, "FLOOR_S", 2)
    tecomat = get("T-01")
    (tmp_path / "ok.il").write_bytes(tecomat.reference.path.read_bytes())
    (tmp_path / "huge.il").write_text("LD X0.0\nWR Y0.0\n" * 1_000_000, encoding="utf-8")
    ok, huge = grade_batch(tecomat, [tmp_path / "ok.il", tmp_path / "huge.il"])
    assert ok.error_kind is None and ok.score == ok.max_score
    assert huge.error_kind == "too slow" and huge.error.startswith("too slow for this exercise: ")


@pytest.mark.parametrize("mode", ["confined", "portable"])
def test_too_slow_is_told_on_both_sandbox_paths(ex1, tmp_path, monkeypatch, mode):
    """The budget binds on the POSIX path (RLIMIT_CPU) and on the portable one (the watchdog), and the
    absolute limit beside it stays a time limit."""
    from plcsim.grading.sandbox.limits import Budget, Limits

    monkeypatch.setenv("PLCSIM_SANDBOX", mode)
    path = tmp_path / "slow.py"
    path.write_text(TOGGLES_FAR_TOO_OFTEN, encoding="utf-8")
    slow = grade_sandboxed(ex1, path, limits=Limits(budget=Budget(1, 0.05)))
    assert (slow.error_kind, slow.error) == ("too slow", Budget(1, 0.05).too_slow())
    capped = grade_sandboxed(ex1, path, limits=Limits(cpu_seconds=1, budget=Budget(10, 0.05)))
    assert (capped.error_kind, capped.error) == ("time limit", "the submission used more than 1 s of CPU time")
