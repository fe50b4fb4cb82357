"""Reports an LMS reads: the JSON report against its published schema (docs/report.schema.json), Gradescope's
results.json, one folder per student for a batch's files, the gradebook's CPU column and one-line
errors, ``plcsim --version`` and ``python -m plcsim``. Exercise 4.3.1 (one 4 s scenario) keeps each grade short.
"""

from __future__ import annotations

import csv
import json
import shutil
import subprocess
import sys
from pathlib import Path

import jsonschema
import pytest

import plcsim
from exercises import get
from plcsim.apps.cli import EXIT_FAILED, main
from plcsim.grading.batch import grade_batch
from plcsim.grading.grader import grade, grade_sandboxed
from plcsim.grading.report import gradescope_results, write_gradebook

SCHEMA = json.loads((Path(__file__).parents[2] / "docs" / "report.schema.json").read_text(encoding="utf-8"))
STOPS_AT_ONCE = "def spin(t):\n    while True:\n        pass\n\n\nOB1 = [spin]\n"
BROKEN = "def OB1(t):\n    t.LED = (\n"


@pytest.fixture(scope="module")
def ex1():
    return get("4.3.1")


def program(folder: Path, name: str, source: str) -> Path:
    path = folder / name
    path.write_text(source, encoding="utf-8")
    return path


@pytest.fixture(scope="module")
def reports(ex1, tmp_path_factory):
    """One report of each outcome: passed, failed, a CPU STOP (with checks not exercised on 4.3.5), a load error."""
    folder = tmp_path_factory.mktemp("subs")
    return {
        "passed": grade(ex1, ex1.reference.path),
        "failed": grade(get("4.3.5"), get("4.3.5").solution("wrong-coil").path),
        "stopped": grade(ex1, program(folder, "stop.py", STOPS_AT_ONCE)),
        "idle": grade(get("4.3.5"), folder / "stop.py", scenarios=["three objects"]),
        "broken": grade(ex1, program(folder, "broken.py", BROKEN)),
        "sandboxed": grade_sandboxed(ex1, ex1.solution("wrong-latch").path),
    }


def test_every_report_is_valid_against_the_published_schema(reports):
    validator = jsonschema.Draft202012Validator(SCHEMA)
    jsonschema.Draft202012Validator.check_schema(SCHEMA)
    for outcome, report in reports.items():
        errors = [e.message for e in validator.iter_errors(json.loads(report.to_json()))]
        assert not errors, (outcome, errors)
    assert {c.status for c in reports["idle"].checks} == {"not exercised", "failed"}


def test_the_schema_refuses_what_a_reader_could_not_rely_on(reports):
    validator = jsonschema.Draft202012Validator(SCHEMA)
    data = json.loads(reports["failed"].to_json())
    assert validator.is_valid(data)
    for broken in (
        {**data, "schema_version": 2},
        {**data, "surprise": 1},  # a new field must be published in the schema
        {k: v for k, v in data.items() if k != "seed"},
        {**data, "error_kind": "bad luck"},
        {**data, "checks": [{**data["checks"][0], "status": "maybe"}]},
    ):
        assert not validator.is_valid(broken)


def test_gradescope_results(reports):
    failed = gradescope_results(reports["failed"], visibility="after_published")
    assert failed["score"] == sum(t["score"] for t in failed["tests"]) == reports["failed"].score
    assert sum(t["max_score"] for t in failed["tests"]) == reports["failed"].max_score == 11.0
    assert {t["status"] for t in failed["tests"]} == {"passed", "failed"}
    assert {t["visibility"] for t in failed["tests"]} == {"after_published"} == {failed["visibility"]}
    stops = next(t for t in failed["tests"] if t["name"] == "three objects: D1 stops when the object reaches S2")
    assert (stops["score"], stops["max_score"], stops["status"]) == (0.0, 1.0, "failed")
    assert stops["output"].startswith("expected S2 rises at least 1 time(s)")
    broken = gradescope_results(reports["broken"])
    assert [(t["name"], t["score"], t["max_score"], t["status"]) for t in broken["tests"]] == [
        ("program error", 0.0, 3.0, "failed")
    ]
    assert "line 2: syntax error" in broken["tests"][0]["output"]
    idle = gradescope_results(reports["idle"])
    not_exercised = [t for t in idle["tests"] if t["tags"] == ["not exercised"]]
    assert len(not_exercised) == len(reports["idle"].not_exercised()) > 0 and idle["score"] == 0.0
    assert {(t["status"], t["score"]) for t in not_exercised} == {("failed", 0.0)}
    assert idle["extra_data"]["max_score"] == reports["idle"].max_score > 0
    assert idle["extra_data"]["plcsim_version"] == plcsim.__version__
    with pytest.raises(ValueError, match="visibility is one of"):
        gradescope_results(reports["failed"], visibility="students")


def test_the_gradebook_names_the_cpu_state_and_errors_on_one_line(reports, tmp_path):
    book = write_gradebook([reports["passed"], reports["stopped"], reports["broken"]], tmp_path / "grades.csv")
    rows = {row["submission"]: row for row in csv.DictReader(book.open(encoding="utf-8"))}
    assert rows["reference.py"]["cpu"] == "RUN"
    assert rows["stop.py"]["cpu"].startswith("STOP in presses: 0 ns: cycle time monitoring exceeded")
    assert rows["broken.py"]["cpu"] == "-"
    assert rows["broken.py"]["error"].startswith("program error: ")
    assert "\n" not in rows["broken.py"]["error"] and rows["broken.py"]["error"].endswith(" …")


def test_a_batch_writes_each_students_files_into_their_folder(ex1, tmp_path):
    subs = tmp_path / "subs"
    subs.mkdir()
    for name in ("alice.py", "bob.py"):
        shutil.copy(ex1.solution("wrong-latch").path, subs / name)
    out = tmp_path / "plots"
    reports = grade_batch(ex1, sorted(subs.glob("*.py")), jobs=2, plots_dir=out)
    assert sorted(p.name for p in out.iterdir()) == ["alice", "bob"]
    for report in reports:
        pngs = sorted((out / report.student).glob("*.png"))
        assert len(pngs) == len(report.failed()) > 0
        assert {c.diagram for c in report.failed()} == {str(p) for p in pngs}


def test_the_command_writes_gradescope_results(ex1, tmp_path, capsys):
    single = tmp_path / "results" / "results.json"
    assert main(["grade", "4.3.1", "--solution", "wrong-latch", "--gradescope", str(single)]) == EXIT_FAILED
    written = json.loads(single.read_text(encoding="utf-8"))
    assert (written["score"], len(written["tests"])) == (0.0, 3)
    subs = tmp_path / "subs"
    subs.mkdir()
    shutil.copy(ex1.reference.path, subs / "alice.py")
    program(subs, "carol.py", BROKEN)
    folder = tmp_path / "gradescope"
    code = main(["grade", "4.3.1", str(subs), "--gradescope", str(folder), "--gradescope-visibility", "hidden"])
    assert code == EXIT_FAILED
    alice = json.loads((folder / "alice" / "results.json").read_text(encoding="utf-8"))
    carol = json.loads((folder / "carol" / "results.json").read_text(encoding="utf-8"))
    assert (alice["score"], alice["visibility"], carol["score"]) == (3.0, "hidden", 0.0)
    capsys.readouterr()


def test_two_submissions_sharing_a_stem_never_overwrite_each_others_files(ex1, tmp_path, capsys):
    """alice.py and alice.il (or Alice.py beside alice.py on a case-blind disk) each keep their own report."""
    subs = tmp_path / "subs"
    subs.mkdir()
    shutil.copy(ex1.reference.path, subs / "alice.py")
    program(subs, "alice.il", "this is not instruction list\n")
    folder, json_dir, plots = tmp_path / "gs", tmp_path / "json", tmp_path / "plots"
    args = ["grade", "4.3.1", str(subs), "--gradescope", str(folder), "--json", str(json_dir), "--plots", str(plots)]
    assert main(args) == EXIT_FAILED
    capsys.readouterr()
    scores = {d.name: json.loads((d / "results.json").read_text(encoding="utf-8"))["score"] for d in folder.iterdir()}
    assert scores == {"alice.py": 3.0, "alice.il": 0.0}
    reports = {p.name: json.loads(p.read_text(encoding="utf-8"))["submission"] for p in json_dir.iterdir()}
    assert {name: Path(sub).name for name, sub in reports.items()} == {
        "alice.py.json": "alice.py",
        "alice.il.json": "alice.il",
    }


def test_version_and_python_m(capsys):
    with pytest.raises(SystemExit) as stop:
        main(["--version"])
    assert stop.value.code == 0 and capsys.readouterr().out == f"plcsim {plcsim.__version__}\n"
    done = subprocess.run([sys.executable, "-m", "plcsim", "--version"], capture_output=True, text=True, timeout=60)
    assert (done.returncode, done.stdout) == (0, f"plcsim {plcsim.__version__}\n")
