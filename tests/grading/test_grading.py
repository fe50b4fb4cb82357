"""Grading (plcsim.grading.grader): scores and failed checks of shipped solutions, the JSON / JUnit / CSV
outputs, hostile submissions in the sandbox (each reported as what it is, never a crash of the
grader), batch grading, and a program that replays fixed times failing under another seed.

The sandbox tests grade exercise 4.3.1 (one 4 s scenario) so that each child process is short.
"""

from __future__ import annotations

import csv
import json
import re
import shutil
from pathlib import Path
from xml.etree import ElementTree as ET

import numpy as np
import pytest
from platforms import PROC

from exercises import get
from plcsim.grading.batch import grade_batch
from plcsim.grading.grader import grade, grade_sandboxed
from plcsim.grading.report import Report, write_gradebook
from plcsim.grading.sandbox.limits import Limits

# one xdist worker runs them in turn: they look for the hostile child's leftovers machine-wide and
# time their limits, so two at once on two cores would see each other
pytestmark = pytest.mark.xdist_group("sandbox")

EX_5 = "4.3.5"
CHECKS_5 = [
    "D1 starts when S1 sees an object",
    "D1 stops when the object reaches S2",
    "transport S1 -> S2 takes 4.8 s +-10 %",
    "the belt starts once per object",
    "the belt never runs while S2 sees an object",
    "no object falls off the belt",
    "the belt stays off without a new object at S1",
]
WRONG_COIL_FAILS = {
    "D1 stops when the object reaches S2",
    "transport S1 -> S2 takes 4.8 s +-10 %",
    "the belt starts once per object",
}


@pytest.fixture(scope="module")
def ex5():
    return get(EX_5)


@pytest.fixture(scope="module")
def ex1():
    return get("4.3.1")


@pytest.fixture(scope="module")
def reference_report(ex5):
    return grade(ex5, ex5.reference.path, seed=1)


@pytest.fixture(scope="module")
def wrong_report(ex5):
    return grade(ex5, ex5.solution("wrong-coil").path, seed=1)


def write(tmp_path: Path, name: str, source: str) -> Path:
    path = tmp_path / name
    path.write_text(source, encoding="utf-8")
    return path


# -- grade() in this process ------------------------------------------------------------------------


def test_reference_of_4_3_5_scores_full_marks(reference_report):
    r = reference_report
    assert (r.exercise, r.title, r.passed, r.score, r.max_score) == (
        "4.3.5",
        "Conveyor control 1 (one object)",
        True,
        11.0,
        11.0,
    )
    assert r.error is None and r.error_kind is None
    assert [(c.scenario, c.check) for c in r.checks] == [
        ("three objects", CHECKS_5[0]),
        ("three objects", CHECKS_5[1]),
        ("three objects", CHECKS_5[2]),
        ("three objects", CHECKS_5[3]),
        ("three objects", CHECKS_5[4]),
        ("three objects", CHECKS_5[5]),
        ("placed mid-belt", CHECKS_5[5]),
        ("placed mid-belt", CHECKS_5[6]),
        ("placed at S2", CHECKS_5[4]),
        ("placed at S2", CHECKS_5[5]),
        ("placed at S2", CHECKS_5[6]),
    ]
    assert all(c.passed and c.points == c.max_points == 1.0 for c in r.checks)
    assert [(run.scenario, run.seed, run.simulated_ns, run.scans, run.cpu_mode, run.cpu_error) for run in r.runs] == [
        ("three objects", 1, 25_000_000_000, 25_000, "RUN", None),
        ("placed mid-belt", 1, 4_000_000_000, 4_000, "RUN", None),
        ("placed at S2", 1, 4_000_000_000, 4_000, "RUN", None),
    ]


def test_wrong_solution_of_4_3_5_fails_the_checks_that_expose_it(wrong_report):
    r = wrong_report
    assert (r.passed, r.score, r.max_score) == (False, 8.0, 11.0)
    assert {c.check for c in r.failed()} == WRONG_COIL_FAILS
    assert all(c.scenario == "three objects" and c.points == 0.0 for c in r.failed())
    assert r.result("the belt starts once per object").message == "expected number of times D1 rises = 3; measured 1"
    stops = r.result("D1 stops when the object reaches S2")
    assert stops.message == (
        "expected S2 rises at least 1 time(s) to check that D1 falls within 1 scan after S2 rises; "
        "it happened 0 time(s)"
    )
    transport = r.result("transport S1 -> S2 takes 4.8 s +-10 %")
    assert transport.message.startswith("after S1 rises at 374 ms, expected S2 rises between 4.32s and 5.28s")
    assert transport.message.endswith("it did not happen afterwards")
    assert transport.at_ns == 374_000_000
    assert transport.signals == ["S1", "S2"]
    with pytest.raises(KeyError, match="no result for check 'nope'"):
        r.result("nope")


def test_only_some_scenarios(ex5):
    r = grade(ex5, ex5.reference.path, scenarios=["placed at S2", "three objects"])
    assert [c.scenario for c in r.checks].count("placed at S2") == 3
    assert (r.score, r.max_score, r.passed) == (9.0, 9.0, True)
    # alone, "placed at S2" (the belt must stay off) cannot tell the reference from a program that does
    # nothing: its checks are not exercised (plcsim.check.exercised)
    alone = grade(ex5, ex5.reference.path, scenarios=["placed at S2"])
    assert [c.status for c in alone.checks] == ["not exercised"] * 3
    assert (alone.score, alone.max_score, alone.passed) == (0.0, 3.0, False)


# -- report formats ---------------------------------------------------------------------------------


def test_report_json_fields(wrong_report, tmp_path):
    path = tmp_path / "report.json"
    text = wrong_report.to_json(path)
    data = json.loads(path.read_text(encoding="utf-8"))
    assert json.loads(text) == data
    assert data["exercise"] == "4.3.5"
    assert data["passed"] is False
    assert (data["score"], data["max_score"]) == (8.0, 11.0)
    assert len(data["checks"]) == 11
    for c in data["checks"]:
        assert {"scenario", "check", "passed", "message"} <= set(c)
        assert isinstance(c["passed"], bool) and c["message"]
    failed = {c["check"] for c in data["checks"] if not c["passed"]}
    assert failed == WRONG_COIL_FAILS
    assert [run["scenario"] for run in data["runs"]] == [
        "three objects",
        "placed mid-belt",
        "placed at S2",
    ]
    assert Report.from_dict(data) == wrong_report


def test_junit_xml_structure(wrong_report, tmp_path):
    path = tmp_path / "report.xml"
    wrong_report.to_junit(path)
    assert path.read_text(encoding="utf-8").startswith('<?xml version="1.0" encoding="utf-8"?>')
    root = ET.parse(path).getroot()
    assert root.tag == "testsuites"
    assert (root.get("name"), root.get("tests"), root.get("failures")) == ("plcsim 4.3.5", "11", "3")
    suites = root.findall("testsuite")
    assert [(s.get("name"), s.get("tests"), s.get("failures")) for s in suites] == [
        ("4.3.5.three objects", "6", "3"),
        ("4.3.5.placed mid-belt", "2", "0"),
        ("4.3.5.placed at S2", "3", "0"),
    ]
    cases = suites[0].findall("testcase")
    assert [c.get("name") for c in cases] == CHECKS_5[:6]
    assert all(c.get("classname") == "wrong-coil.4.3.5.three objects" for c in cases)  # the student first
    failures = {c.get("name"): c.find("failure") for c in cases if c.find("failure") is not None}
    assert set(failures) == WRONG_COIL_FAILS
    f = failures["the belt starts once per object"]
    assert (f.get("type"), f.get("message"), f.text) == (
        "check failed",
        "expected number of times D1 rises = 3; measured 1",
        "expected number of times D1 rises = 3; measured 1",
    )


def test_junit_of_a_submission_that_did_not_load(ex1, tmp_path):
    report = grade(ex1, write(tmp_path, "bad.py", "import os\n"))
    root = ET.fromstring(report.to_junit())
    (suite,) = root.findall("testsuite")
    (case,) = suite.findall("testcase")
    assert (suite.get("tests"), suite.get("failures"), suite.get("errors"), case.get("name")) == ("1", "0", "1", "load")
    assert case.get("classname") == "bad.4.3.1" and case.find("failure") is None
    error = case.find("error")  # a submission that did not load is an error, not a failed check
    assert error.get("type") == "subset violation"
    assert "imports are not part of PLC programs" in error.get("message")
    assert (root.get("tests"), root.get("failures"), root.get("errors")) == ("1", "0", "1")


def test_gradebook_rows(reference_report, wrong_report, ex1, tmp_path):
    broken = grade(ex1, write(tmp_path, "broken.py", "def OB1(t):\n    t.LED = (\n"))
    path = write_gradebook([reference_report, wrong_report, broken], tmp_path / "grades.csv")
    rows = list(csv.reader(path.open(encoding="utf-8")))
    header = rows[0]
    assert header[:7] == ["submission", "score", "max_score", "percent", "passed", "error", "cpu"]
    assert len(header) == 7 + 11  # one column per scenario and check
    assert header[7] == "three objects: D1 starts when S1 sees an object"
    assert rows[1][:7] == ["reference.py", "11", "11", "100.0", "yes", "", "RUN"]
    assert rows[1][7:] == ["pass"] * 11
    assert rows[2][:7] == ["wrong-coil.py", "8", "11", "72.7", "no", "", "RUN"]
    assert rows[2][7:].count("FAIL") == 3
    assert rows[3][:5] == ["broken.py", "0", "3", "0.0", "no"]
    assert rows[3][5].startswith("program error: ") and "line 2: syntax error" in rows[3][5]
    assert "\n" not in rows[3][5] and rows[3][6] == "-"  # one line; the CPU never ran
    assert rows[3][7:] == ["-"] * 11
    assert len(rows) == 4


# -- hostile submissions in the sandbox -----------------------------------------------------------------


@pytest.mark.parametrize(
    ("source", "line", "message"),
    [
        ("import os\n\ndef OB1(t):\n    t.LED = t.TLACIDLO\n", 1, "imports are not part of PLC programs"),
        ("from socket import socket\n\ndef OB1(t):\n    pass\n", 1, "imports are not part of PLC programs"),
        ('def OB1(t):\n    f = open("/etc/passwd")\n', 2, r"open is not available in PLC programs \(no file, network"),
        ('def OB1(t):\n    t.LED = eval("1")\n', 2, "eval is not available in PLC programs"),
        ('def OB1(t):\n    exec("import os")\n', 2, "exec is not available in PLC programs"),
        ('def OB1(t):\n    os = __import__("os")\n', 2, r"names starting with _ are reserved \(__import__\)"),
        ("def OB1(t):\n    x = t.__class__\n", 2, r"the attribute .__class__ is not available in PLC programs"),
        ("def OB1(t):\n    x = ().__class__.__bases__\n", 2, r"the attribute .__(bases|class)__ is not available"),
        ("def OB1(t):\n    g = OB1.__globals__\n", 2, r"the attribute .__globals__ is not available"),
        ('def OB1(t):\n    x = "{0.__class__}".format(t)\n', 2, r"the attribute .format is not available"),
        ('def OB1(t):\n    t.LED = getattr(t, "TLACIDLO")\n', 2, "getattr is not available in PLC programs"),
    ],
    ids=[
        "import",
        "from-import",
        "open",
        "eval",
        "exec",
        "__import__",
        "dunder",
        "bases",
        "globals",
        "format",
        "getattr",
    ],
)
def test_subset_violations_are_reported_as_such(ex1, tmp_path, source, line, message):
    path = write(tmp_path, "hostile.py", source)
    r = grade_sandboxed(ex1, path)
    assert r.error_kind == "subset violation"
    assert r.error.startswith(f"{path}, line {line}: ")
    assert re.search(message, r.error), r.error
    assert (r.passed, r.score, r.max_score, r.checks, r.runs) == (False, 0.0, 3.0, [], [])


def test_a_syntax_error_is_reported_with_its_line(ex1, tmp_path):
    path = write(tmp_path, "syntax.py", "def OB1(t):\n    t.LED = t.TLACIDLO\n    if t.LED\n        pass\n")
    r = grade_sandboxed(ex1, path)
    assert r.error_kind == "program error"
    assert r.error.startswith(f"{path}, line 3: syntax error: ")
    assert (r.passed, r.score, r.max_score) == (False, 0.0, 3.0)


def test_an_endless_loop_is_stopped_by_the_cycle_watchdog(ex1, tmp_path):
    path = write(tmp_path, "loop.py", "def OB1(t):\n    t.LED = t.TLACIDLO\n    while True:\n        pass\n")
    r = grade_sandboxed(ex1, path)
    assert r.error is None  # the grading itself finished
    (run,) = r.runs
    assert (run.scenario, run.cpu_mode, run.scans) == ("presses", "STOP", 0)
    assert run.cpu_error.startswith("0 ns: cycle time monitoring exceeded [OB1 network 1 (OB1), line 3]")
    assert "the program loops without end; the watchdog" in run.cpu_error
    assert not r.passed and r.score < r.max_score == 3.0
    for c in r.failed():
        assert c.message.endswith(f" [the CPU stopped: {run.cpu_error}]")


def test_an_exception_in_a_network_stops_the_cpu_and_is_graded(ex1, tmp_path):
    source = "def OB1(t):\n    t.LED = t.TLACIDLO\n    if t.TLACIDLO:\n        x = [1, 2][5]\n"
    r = grade_sandboxed(ex1, write(tmp_path, "exc.py", source))
    assert r.error is None
    (run,) = r.runs
    assert run.cpu_mode == "STOP"
    assert "error in the program [OB1 network 1 (OB1), line 4]" in run.cpu_error
    assert "IndexError" in run.cpu_error
    assert not r.passed
    assert "every press is reproduced on the LED" in {c.check for c in r.failed()}


def vm_size_mb(pid: int | str = "self") -> int:
    for line in Path(f"/proc/{pid}/status").read_text(encoding="utf-8").splitlines():
        if line.startswith("VmSize:"):
            return int(line.split()[1]) // 1024
    return 2048


def child_start_mb(ex1) -> int:
    """The address space a grading child starts with: its fork server's (Linux), else this process's as a
    bound. (This process's own grows with its threads' arenas: as a limit it once let the bomb run into the
    time limit.)"""
    from plcsim.grading.sandbox import forkserver

    grade_sandboxed(ex1, ex1.reference.path)  # starts the fork server, if there is one
    servers = [s for s in forkserver._SERVERS.values() if s.alive]
    return max(vm_size_mb(s.process.pid) for s in servers) if servers else vm_size_mb()


@PROC  # the limit is set above the child's starting address space, read in /proc
def test_a_memory_bomb_hits_the_memory_limit(ex1, tmp_path):
    source = "def OB1(t):\n    x = [0]\n    for i in range(40):\n        x = x + x\n    t.LED = t.TLACIDLO\n"
    limits = Limits(memory_mb=child_start_mb(ex1) + 300, cpu_seconds=20, wall_seconds=60)
    r = grade_sandboxed(ex1, write(tmp_path, "bomb.py", source), limits=limits)
    assert not r.passed
    if r.error_kind is not None:  # the grader itself ran out of memory
        assert r.error_kind == "memory limit"
        assert r.error == f"the submission ran out of memory (the limit is {limits.memory_mb} MB)"
    else:  # the network's allocation failed: the CPU stopped with a MemoryError
        (run,) = r.runs
        assert run.cpu_mode == "STOP"
        assert "MemoryError" in run.cpu_error


def test_a_cpu_hog_hits_the_time_limit(ex1, tmp_path):
    source = "def OB1(t):\n    x = 0\n    for i in range(300000):\n        x = x + i\n    t.LED = t.TLACIDLO\n"
    r = grade_sandboxed(ex1, write(tmp_path, "hog.py", source), limits=Limits(cpu_seconds=2, wall_seconds=30))
    assert (r.error_kind, r.error) == ("time limit", "the submission used more than 2 s of CPU time")
    assert (r.passed, r.score, r.max_score) == (False, 0.0, 3.0)
    assert 1.5 < r.elapsed_s < 29  # 2 s of CPU time (wall time depends on the load)


def test_the_wall_time_limit(ex1, tmp_path):
    source = "def OB1(t):\n    x = 0\n    for i in range(300000):\n        x = x + i\n"
    r = grade_sandboxed(ex1, write(tmp_path, "slow.py", source), limits=Limits(cpu_seconds=60, wall_seconds=1))
    assert (r.error_kind, r.error) == ("time limit", "no result within 1 s of wall time")
    assert r.elapsed_s < 10


def test_a_program_that_redeclares_an_exercise_tag(ex1, tmp_path):
    path = write(tmp_path, "dup.py", "LED = Bool(False)\n\ndef OB1(t):\n    t.LED = t.TLACIDLO\n")
    r = grade_sandboxed(ex1, path)
    assert r.error_kind == "program error"
    assert r.error == (
        f"{path}: 'LED' is already declared by exercise 4.3.1; use the existing tag or choose another name"
    )


def test_a_good_submission_passes_in_the_sandbox(ex1):
    r = grade_sandboxed(ex1, ex1.reference.path)
    assert (r.passed, r.score, r.max_score, r.error) == (True, 3.0, 3.0, None)
    assert r.submission == str(ex1.reference.path)


# -- batches ------------------------------------------------------------------------------------------------


def test_grade_batch_with_a_broken_submission(ex1, tmp_path):
    folder = tmp_path / "submissions"
    folder.mkdir()
    shutil.copy(ex1.reference.path, folder / "a_good.py")
    shutil.copy(ex1.solution("wrong-latch").path, folder / "b_wrong.py")
    write(folder, "c_broken.py", "def OB1(t):\n    t.LED = t.TLACIDLO +\n")
    seen = []
    reports = grade_batch(
        ex1, sorted(folder.glob("*.py")), jobs=2, progress=lambda done, total, r: seen.append((done, total))
    )
    assert [Path(r.submission).name for r in reports] == ["a_good.py", "b_wrong.py", "c_broken.py"]
    good, wrong, broken = reports
    assert (good.passed, good.score, good.max_score) == (True, 3.0, 3.0)
    assert (wrong.passed, wrong.error) == (False, None)
    assert "LED equals the button in every scan" in {c.check for c in wrong.failed()}
    assert (broken.passed, broken.error_kind, broken.score, broken.max_score) == (False, "program error", 0.0, 3.0)
    assert "line 2: syntax error" in broken.error
    assert sorted(seen) == [(1, 3), (2, 3), (3, 3)]
    book = write_gradebook(reports, tmp_path / "grades.csv")
    rows = list(csv.reader(book.open(encoding="utf-8")))
    assert [row[0] for row in rows[1:]] == ["a_good.py", "b_wrong.py", "c_broken.py"]
    assert [row[4] for row in rows[1:]] == ["yes", "no", "no"]


# -- anti-hard-coding ------------------------------------------------------------------------------------------


def replay_program(ex5) -> str:
    """A program that switches D1 on and off at the scans where the reference did (seed 1), counting scans.

    It waits for S1 once, so that the scenarios without a part at S1 pass too: with seed 1 it is
    indistinguishable from the reference."""
    sim = ex5.simulation(ex5.reference.program(), "three objects", seed=1)
    sim.run()
    tr = sim.trace
    assert (np.diff(tr.times) == 1_000_000).all() and tr.times[0] == 0  # row k is the scan at k ms
    on = tr.column("D1")
    spans, k = [], 0
    while k < len(on):
        if on[k]:
            j = k
            while j + 1 < len(on) and on[j + 1]:
                j += 1
            spans.append((k, j + 1))
            k = j + 1
        else:
            k += 1
    assert len(spans) == 3
    when = " or ".join(f"({a} <= t.N and t.N < {b})" for a, b in spans)
    return (
        "N = DInt(0)\nSEEN = Bool(False)\n\n\n"
        "def OB1(t):\n"
        "    if t.S1:\n"
        "        t.SEEN = True\n"
        f"    t.D1 = t.SEEN and ({when})\n"
        "    t.N = t.N + 1\n"
    )


def test_a_program_replaying_fixed_times_fails_with_another_seed(ex5, tmp_path):
    path = write(tmp_path, "replay.py", replay_program(ex5))
    same = grade(ex5, path, seed=1)
    # recorded from "three objects" on seed 1: there it passes, and the other scenarios keep the belt off
    assert same.passed
    for seed in (2, 3):
        other = grade(ex5, path, seed=seed)
        assert not other.passed, seed
        failed = {c.check for c in other.failed()}
        assert "D1 stops when the object reaches S2" in failed
        assert "the belt never runs while S2 sees an object" in failed
        assert other.score <= 8.0
        reference = grade(ex5, ex5.reference.path, seed=seed)
        assert reference.passed  # the scenario changed, the task did not


def test_grading_samples_drawing_frames_only_for_a_recording():
    """No check reads the plant's drawing frames, so a run nobody will watch samples none; the trace rows and
    events (what is graded) are the same bit for bit."""
    from plcsim.grading import run_scenarios

    ex = get("4.3.5")
    first = [ex.scenarios[0].name]
    (watched,), _ = run_scenarios(ex, ex.reference.program(), seed=1, scenarios=first)
    (graded,), _ = run_scenarios(ex, ex.reference.program(), seed=1, scenarios=first, geometry=False)
    assert watched.trace.frames and not graded.trace.frames
    assert watched.trace.digest() == graded.trace.digest()
