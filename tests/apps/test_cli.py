"""The ``plcsim`` command: list, show, run, grade (single, batch), its files and exit codes.

Most calls go through ``plcsim.apps.cli.main([...])`` in this process; one runs the installed entry point.
"""

from __future__ import annotations

import csv
import json
import shutil
import subprocess
import time
from xml.etree import ElementTree as ET

import numpy as np
import pytest
from platforms import UTF8, console_script, utf8_env

from exercises import get
from plcsim.apps.cli import EXIT_FAILED, EXIT_USAGE, main
from plcsim.trace.facade import Trace


@pytest.fixture(autouse=True)
def wide_console(monkeypatch):
    """rich wraps at 80 columns when it writes to a pipe; the assertions want whole lines."""
    monkeypatch.setenv("COLUMNS", "250")


def test_help(capsys):
    with pytest.raises(SystemExit) as info:
        main(["--help"])
    assert info.value.code == 0
    out = capsys.readouterr().out
    assert out.startswith("usage: plcsim [-h] [--version] COMMAND ...")
    for command in ("list", "show", "run", "grade"):
        assert f"\n    {command} " in out


def test_no_command_prints_help_and_fails(capsys):
    assert main([]) == EXIT_USAGE
    assert capsys.readouterr().out.startswith("usage: plcsim")


def test_list(capsys, monkeypatch):
    monkeypatch.setenv("COLUMNS", "200")  # wide enough for the table
    assert main(["list"]) == 0
    out = capsys.readouterr().out
    for ex in ("4.3.1", "4.3.5", "conveyor-1", "led-1", "LED control 1 (NO push-button)"):
        assert ex in out
    numbers = [line.split("│")[1].strip() for line in out.splitlines() if line.startswith("│ 4.3.")]
    assert numbers[:2] == ["4.3.1", "4.3.2"]
    assert numbers == sorted(numbers, key=lambda n: tuple(int(p) for p in n.split(".")))


@pytest.mark.parametrize("width", [40, 80, 120])
@pytest.mark.parametrize("command", [["list"], ["list", "--profiles"]])
def test_list_never_cuts_a_name_at_any_width(command, width, capsys, monkeypatch):
    """At 80 columns the table cut names (``wrong-no-con…``); now it becomes a list where it does not fit."""
    monkeypatch.setenv("COLUMNS", str(width))
    assert main(command) == 0
    out = capsys.readouterr().out
    assert "…" not in out
    words = set(out.split())
    if command == ["list"]:
        for ex in get("4.3.2"), get("6.3.3"):
            assert ex.number in words and ex.slug in words
            assert all(s.name in words or f"{s.name}," in words for s in ex.solutions)
    else:
        assert {"s7-1200", "tecomat-ns950"} <= words


def test_show(capsys):
    """The student's view by default: the task, its requirements with the checks that grade each, and no shipped
    program or instructor's note (they give the reference's logic away)."""
    assert main(["show", "4.3.5"]) == 0
    out = " ".join(capsys.readouterr().out.split())  # the terminal's width must not matter
    assert "4.3.5 Conveyor control 1 (one object)" in out
    for text in (
        "I/O table",
        "%I0.0",
        "%Q0.2",
        "three objects (25 s)",
        "placed mid-belt (4 s)",
        'Requirements (the words of the task each check grades) 1. "Carry it to the end of the conveyor, where S2 '
        'detects it" • transport S1 -> S2 takes 4.8 s +-10 % (three objects)',
        '3. "stop it in the scan in which S2 detects it" • D1 stops when the object reaches S2 (three objects)',
    ):
        assert text in out, text
    for check in get("4.3.5").checks:
        assert f'"{" ".join(check.requirement.split())}"' in out, check.name
    for hidden in ("Shipped programs", "reference [reference]", "wrong-coil", "SET D1"):
        assert hidden not in out, hidden


def test_show_states_what_the_task_assumes_and_the_scenarios_that_leave_it(capsys):
    """Every operating condition is printed with the task's words, and a scenario outside one (or injecting a
    fault) says which and what the task says must happen then."""
    assert main(["show", "4.3.17"]) == 0
    out = " ".join(capsys.readouterr().out.split())
    assert "The task assumes (a scenario that leaves it says so above, with the task's words)" in out
    assert get("4.3.17").conditions
    for condition in get("4.3.17").conditions:
        assert f'• "{" ".join(condition.words.split())}"' in out
    too_close = get("4.3.17").scenario("objects too close")
    ((left, then),) = too_close.outside.items()
    assert f'leaves "{" ".join(left.split())}"; the task says: "{" ".join(then.split())}"' in out
    assert 'injects a fault; the task says: "also when the compressor fails to build pressure"' in out


def test_show_solutions_is_the_instructors_view(capsys):
    assert main(["show", "6.3.3", "--solutions"]) == 0
    out = " ".join(capsys.readouterr().out.split())
    for text in (
        "reference [reference]: S M2_DOLE for an object at OS2",  # the kind is text, not Rich markup
        "wrong-no-ks1-interlock [wrong]",
        "notes for instructors",
    ):
        assert text in out, text
    assert main(["show", "6.3.3"]) == 0
    student = " ".join(capsys.readouterr().out.split())
    assert "S M2_DOLE" not in student and "notes for instructors" not in student
    assert "the next stroke starts only once the press is at the top (KS1)" in student


def test_show_by_slug(capsys):
    assert main(["show", "conveyor-1"]) == 0
    assert "4.3.5 Conveyor control 1" in capsys.readouterr().out


def test_a_bad_exercise_name(capsys):
    assert main(["show", "4.3.55"]) == EXIT_USAGE
    err = capsys.readouterr().err
    assert "error: no exercise '4.3.55'; did you mean '4.3.5'" in err
    assert "`plcsim list` shows them all" in err
    assert main(["grade", "conveyor1", "--reference"]) == EXIT_USAGE
    assert "did you mean 'conveyor-1'" in capsys.readouterr().err


def test_run_the_reference_with_all_outputs(tmp_path, capsys):
    rrd, png, npz = tmp_path / "out" / "run.rrd", tmp_path / "out" / "run.png", tmp_path / "run.npz"
    code = main(["run", "4.3.5", "--reference", "--rrd", str(rrd), "--plot", str(png), "--trace", str(npz)])
    out = capsys.readouterr().out
    assert code == 0
    assert "running 4.3.5, scenario 'three objects' for 25 s simulated" in out
    assert "25000 scans, CPU RUN" in out
    assert f"recording: {rrd}" in out and f"timing diagram: {png}" in out and f"trace: {npz}" in out
    assert "grade of this run (scenario 'three objects', seed 1):" in out
    assert "6 / 6 points, 6/6 checks passed" in out
    assert rrd.stat().st_size > 10_000
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    trace = Trace.load(npz)
    assert trace.meta["seed"] == 1 and trace.meta["scenario"] == "three objects"
    assert len(trace) == 25_000
    assert trace.rises("D1").tolist() == [375_000_000, 7_256_000_000, 14_621_000_000]
    assert np.array_equal(trace.rises("S1"), trace.rises("D1") - 1_000_000)


def test_run_a_wrong_solution_fails(capsys):
    assert main(["run", "4.3.5", "--solution", "wrong-coil"]) == EXIT_FAILED
    out = capsys.readouterr().out
    assert "3 / 6 points, 3/6 checks passed" in out
    assert "expected number of times D1 rises = 3; measured 1" in out


def test_run_another_scenario_and_seed(capsys):
    assert main(["run", "4.3.5", "--reference", "--scenario", "placed at S2", "--seed", "4"]) == 0
    out = capsys.readouterr().out
    assert "scenario 'placed at S2' for 4 s simulated" in out
    assert "grade of this run (scenario 'placed at S2', seed 4):" in out
    assert "3 / 3 points" in out


def test_run_a_bare_rig_with_a_program(tmp_path, capsys):
    program = tmp_path / "belt.py"
    program.write_text("def OB1(t):\n    t.D1 = not t.S2\n", encoding="utf-8")
    assert main(["run", "CONV1", "--program", str(program), "--seconds", "5"]) == 0
    out = capsys.readouterr().out
    assert "running CONV1 for 5 s simulated" in out
    assert "5000 scans, CPU RUN" in out
    assert "grade of this run" not in out  # a bare rig has no checks


def test_run_a_bare_rig_without_a_program_operates_it_by_hand(tmp_path, capsys):
    """A student explores a machine before writing a program: the rig runs with every output off, and a
    saved session's presses and parts act on it."""
    trace = tmp_path / "by-hand.npz"
    assert main(["run", "CONV1", "--seconds", "2", "--trace", str(trace)]) == 0
    assert "2000 scans, CPU RUN" in capsys.readouterr().out
    assert not Trace.load(trace).column("D1").any()


def test_live_without_a_program_runs_the_empty_one():
    from plcsim.apps.live.session import NO_PROGRAM, LiveSession

    session = LiveSession("CONV1", NO_PROGRAM)
    session.advance(500_000_000)
    assert session.sim.cpu.mode == "RUN" and session.sim.cpu.outputs["D1"] is False


def test_run_in_real_time(capsys):
    started = time.perf_counter()
    assert main(["run", "4.3.1", "--reference", "--realtime", "8"]) == 0
    wall = time.perf_counter() - started
    out = capsys.readouterr().out
    assert "for 4 s simulated at 8× real time" in out
    assert wall >= 0.45  # 4 s simulated at 8x


def test_grade_the_reference_with_json_and_junit(tmp_path, capsys):
    js, xml = tmp_path / "r" / "report.json", tmp_path / "r" / "report.xml"
    assert main(["grade", "4.3.5", "--reference", "--json", str(js), "--junit", str(xml)]) == 0
    out = capsys.readouterr().out
    assert "PASSED  score 11 / 11" in out
    data = json.loads(js.read_text(encoding="utf-8"))
    assert (data["exercise"], data["passed"], data["score"], data["max_score"]) == ("4.3.5", True, 11.0, 11.0)
    assert len(data["checks"]) == 11
    assert all(set(c) >= {"scenario", "check", "passed", "message"} and c["passed"] for c in data["checks"])
    root = ET.parse(xml).getroot()
    assert (root.tag, root.get("tests"), root.get("failures")) == ("testsuites", "11", "0")
    assert len(root.findall("testsuite/testcase")) == 11


def test_grade_a_wrong_solution_exits_1(tmp_path, capsys):
    path = tmp_path / "mine.py"
    shutil.copy(get("4.3.5").solution("wrong-coil").path, path)
    js = tmp_path / "mine.json"
    assert main(["grade", "4.3.5", str(path), "--json", str(js), "-v"]) == EXIT_FAILED
    out = capsys.readouterr().out
    assert "FAILED  score 8 / 11" in out
    assert "expected number of times D1 rises = 3; measured 1" in out
    data = json.loads(js.read_text(encoding="utf-8"))
    assert (data["passed"], data["score"]) == (False, 8.0)
    assert data["submission"] == str(path)


def test_grade_without_a_submission(capsys):
    assert main(["grade", "4.3.5"]) == EXIT_USAGE
    assert "give a submission file or folder, or --reference / --solution NAME" in capsys.readouterr().err


def test_grade_a_hostile_submission_is_reported(tmp_path, capsys):
    path = tmp_path / "evil.py"
    path.write_text("import os\n\ndef OB1(t):\n    os.system('true')\n", encoding="utf-8")
    js = tmp_path / "evil.json"
    assert main(["grade", "4.3.1", str(path), "--json", str(js)]) == EXIT_FAILED
    data = json.loads(js.read_text(encoding="utf-8"))
    assert data["error_kind"] == "subset violation"
    assert "line 1: imports are not part of PLC programs" in data["error"]
    assert (data["score"], data["max_score"], data["checks"]) == (0.0, 3.0, [])


def test_grade_a_folder_in_a_batch(tmp_path, capsys):
    ex = get("4.3.1")
    folder = tmp_path / "class"
    folder.mkdir()
    shutil.copy(ex.reference.path, folder / "alice.py")
    shutil.copy(ex.solution("wrong-latch").path, folder / "bob.py")
    (folder / "carol.py").write_text("def OB1(t)\n    t.LED = t.TLACIDLO\n", encoding="utf-8")
    (folder / "notes.txt").write_text("not a program", encoding="utf-8")
    book, reports = tmp_path / "grades.csv", tmp_path / "reports"
    code = main(["grade", "4.3.1", str(folder), "--jobs", "2", "--gradebook", str(book), "--json", str(reports)])
    out = capsys.readouterr().out
    assert code == EXIT_FAILED  # not every submission passed
    assert "alice.py: 3/3" in out and "bob.py: " in out
    assert "carol.py: 0/3  program error: " in out
    rows = list(csv.reader(book.open(encoding="utf-8")))
    assert [r[0] for r in rows[1:]] == ["alice.py", "bob.py", "carol.py"]
    assert [r[4] for r in rows[1:]] == ["yes", "no", "no"]
    assert "line 1: syntax error" in rows[3][5]
    assert sorted(p.name for p in reports.iterdir()) == ["alice.json", "bob.json", "carol.json"]
    assert json.loads((reports / "alice.json").read_text(encoding="utf-8"))["passed"] is True


def test_grade_an_empty_folder(tmp_path, capsys):
    assert main(["grade", "4.3.1", str(tmp_path)]) == EXIT_USAGE
    assert f"no program files (.il, .mech, .py) in {tmp_path}" in capsys.readouterr().err


def test_the_installed_entry_point(tmp_path):
    exe = console_script("plcsim")
    assert exe.is_file(), "plcsim is not installed in this environment (pip install -e .)"
    js = tmp_path / "report.json"
    env = utf8_env(COLUMNS="200")
    done = subprocess.run(
        [str(exe), "grade", "4.3.1", "--reference", "--json", str(js)],
        capture_output=True,
        **UTF8,
        env=env,
        timeout=120,
        cwd=tmp_path,  # not the project folder: the installed package must find its exercises
    )
    assert done.returncode == 0, done.stderr
    assert "PASSED  score 3 / 3" in done.stdout
    assert json.loads(js.read_text(encoding="utf-8"))["passed"] is True
    bad = subprocess.run([str(exe), "show", "4.3.99"], capture_output=True, **UTF8, env=env, timeout=60)
    assert bad.returncode == EXIT_USAGE
    assert "error: no exercise '4.3.99'" in bad.stderr


@pytest.mark.parametrize("width", [60, 80, 120])
@pytest.mark.parametrize("number", ["4.3.17", "6.3.3", "4.3.16", "P-02"])
def test_show_never_cuts_a_tag_name_at_any_width(number, width, capsys, monkeypatch):
    """At 80 columns the I/O table cut tag names (``OS2_Detekc…``, ``Piest1_Far…``) and the panel's border a
    long title; every name and the whole title are there now."""
    monkeypatch.setenv("COLUMNS", str(width))
    assert main(["show", number]) == 0
    out = capsys.readouterr().out
    words = set(out.replace("│", " ").split())
    missing = [row["tag"] for row in get(number).describe_io() if row["tag"] not in words]
    assert not missing, f"cut or broken at {width} columns: {missing}"
    assert get(number).title in " ".join(out.replace("─", " ").split())


def test_a_grade_report_leads_with_the_verdict_and_the_earliest_failure(capsys, monkeypatch):
    """A passing 4.3.17 printed 347 lines; now the verdict comes first, then the failed checks in the order
    of their first violation, one line per scenario; -q leaves the verdict and the failed names, -v all."""
    monkeypatch.setenv("COLUMNS", "120")
    assert main(["grade", "4.3.5", "--solution", "wrong-coil", "--no-sandbox"]) == EXIT_FAILED
    lines = capsys.readouterr().out.splitlines()
    assert lines[1].startswith("FAILED  score 8 / 11") and lines[-1].startswith("FAILED  score 8 / 11")
    failed = [line for line in lines if line.startswith("✗ three objects: ") and "/" not in line.split(":")[1]]
    assert failed[0] == "✗ three objects: transport S1 -> S2 takes 4.8 s +-10 %"  # violated first, at 374 ms
    assert len(lines) < 25
    assert main(["grade", "4.3.5", "--solution", "wrong-coil", "--no-sandbox", "-q"]) == EXIT_FAILED
    quiet = capsys.readouterr().out.splitlines()
    assert quiet[1].startswith("FAILED") and len(quiet) == 2 + 3 and all(q.startswith("✗ ") for q in quiet[2:])
    assert main(["grade", "4.3.5", "--solution", "wrong-coil", "--no-sandbox", "-v"]) == EXIT_FAILED
    verbose = capsys.readouterr().out
    assert "points" in verbose and verbose.count("✓ ") >= 8  # the table of every check, and why each passed
