"""The grading child as a hostile process (plcsim.grading.sandbox.parent, plcsim.grading.sandbox.confine): a
test-double child (``tests/sandbox_hostile_child.py``, started through ``grade_sandboxed(child_entry=...)``) does
what a submission that escaped the compiler could do. The grader must refuse every forged result, kill
what the child leaves behind, keep nothing on disk and report the true outcome.

Exercise 4.3.1 (one 4 s scenario, 3 points) keeps each child short.
"""

from __future__ import annotations

import json
import os
import socket
import sys
import tempfile
import time
from pathlib import Path

import pytest
from platforms import NAMESPACES

from exercises import get
from plcsim.core.errors import ConfigurationError
from plcsim.grading.grader import grade_sandboxed
from plcsim.grading.sandbox import forkserver
from plcsim.grading.sandbox.limits import Limits

# one xdist worker runs them in turn: they look for the hostile child's leftovers machine-wide and
# time their limits, so two at once on two cores would see each other
pytestmark = pytest.mark.xdist_group("sandbox")

HOSTILE = "sandbox_hostile_child"


@pytest.fixture(scope="module")
def ex1():
    return get("4.3.1")


def hostile(ex1, tmp_path, order, limits=None):
    path = tmp_path / "order.py"
    path.write_text(json.dumps(order), encoding="utf-8")
    return grade_sandboxed(ex1, path, child_entry=HOSTILE, limits=limits)


@pytest.fixture(params=["forked", "fresh"])
def start(request, monkeypatch):
    """Both ways a child starts: forked from the fork server (Linux) and as a fresh interpreter."""
    if request.param == "fresh":
        monkeypatch.setenv(forkserver.VARIABLE, "off")
    return request.param


@pytest.fixture
def private_tmp(tmp_path, monkeypatch):
    """A temporary folder of this test's own, for the grader's scratch folders (the machine's /tmp is shared)."""
    folder = tmp_path / "tmp"
    folder.mkdir()
    monkeypatch.setattr(tempfile, "tempdir", str(folder))
    return folder


def test_the_control_an_honest_trace_of_the_reference_gets_full_marks(ex1, tmp_path):
    r = hostile(ex1, tmp_path, {"do": "reference"})
    assert (r.error_kind, r.passed, r.score, r.max_score) == (None, True, 3.0, 3.0)


@pytest.mark.parametrize(
    ("order", "why"),
    [
        ({"do": "garbage"}, "does not start with the result marker"),
        ({"do": "pickle"}, "does not start with the result marker"),  # never unpickled
        ({"do": "tamper", "how": "bool-two"}, "the Bool signal 'TLACIDLO' holds values other than 0 and 1"),
        ({"do": "tamper", "how": "truncated"}, "the child's result is incomplete"),
    ],
    ids=["garbage", "pickle", "bool-two", "truncated"],
)
def test_a_forged_message_on_the_pipe_is_an_invalid_result(ex1, tmp_path, order, why):
    """(Every other forgery is refused by the same decoder: see test_sandbox_results.py.)"""
    r = hostile(ex1, tmp_path, order)
    assert (r.error_kind, r.passed, r.score, r.max_score, r.checks) == ("invalid result", False, 0.0, 3.0, [])
    assert why in r.error, r.error


def test_forged_passed_lines_on_stdout_and_stderr_count_for_nothing(ex1, tmp_path, capfd):
    r = hostile(ex1, tmp_path, {"do": "print-passed"})
    assert (r.error_kind, r.passed, r.score) == ("crash", False, 0.0)
    assert r.error == "the grading process exited with code 0 without sending a result"
    out, err = capfd.readouterr()
    assert "PASSED" not in out + err  # the child's output is not even shown


def process_alive(pid: int) -> bool:
    try:
        state = Path(f"/proc/{pid}/stat").read_text(encoding="utf-8").split(") ")[1][0]
    except (FileNotFoundError, IndexError):
        return False
    return state != "Z"


@NAMESPACES
def test_a_grandchild_that_leaves_the_group_and_holds_the_pipe_neither_delays_the_grade_nor_survives(
    ex1, tmp_path, start
):
    pid_file = tmp_path / "grandchild.pid"
    started = time.perf_counter()
    r = hostile(ex1, tmp_path, {"do": "grandchild", "pid_file": str(pid_file)})
    assert time.perf_counter() - started < 4  # the grandchild sleeps 60 s holding the pipe
    assert (r.error_kind, r.error) == ("crash", "the grading process exited with code 3 without sending a result")
    sleeper = int(pid_file.read_text(encoding="utf-8"))  # it was started (its pid outside the child's PID namespace)
    deadline = time.monotonic() + 10  # (it dies at once; a loaded machine may take a while to say so)
    while process_alive(sleeper) and time.monotonic() < deadline:
        time.sleep(0.05)
    assert not process_alive(sleeper)


@NAMESPACES
def test_after_the_lock_down_nothing_secret_is_read_nothing_written_outside_scratch_nothing_forks_or_connects(
    ex1, tmp_path, private_tmp, start
):
    outside = tmp_path / "outside"
    outside.mkdir()
    other_student = tmp_path / "other.py"  # beside the submission: another student's file
    other_student.write_text("def OB1(t):\n    t.LED = t.TLACIDLO\n", encoding="utf-8")
    listener = socket.create_server(("127.0.0.1", 0))
    port = listener.getsockname()[1]
    secrets = [str(ex1.reference.path), str(ex1.solution("wrong-latch").path), str(other_student)]
    targets = [str(outside / "note.txt"), str(private_tmp / "escape.txt")]
    try:
        r = hostile(ex1, tmp_path, {"do": "escape", "read": secrets, "write": targets, "port": port})
    finally:
        listener.close()
    assert (r.error_kind, r.passed, r.score) == (None, True, 3.0)  # the run itself is the reference's
    tried = r.warnings
    assert [t.split(":")[0] for t in tried] == (
        [f"read {t}" for t in secrets] + [f"write {t}" for t in targets] + ["fork", "connect"]
    )
    assert all("PermissionError" in t for t in tried[:5]), tried
    assert tried[5] in ("fork: BlockingIOError", "fork: PermissionError"), tried
    assert tried[6].startswith("connect: "), tried
    assert list(outside.iterdir()) == []
    assert list(private_tmp.iterdir()) == []  # nothing in the temporary folder, the scratch folder is gone too


def test_an_exit_without_result_is_a_crash_with_its_exit_code_and_leaves_no_scratch(ex1, tmp_path, private_tmp, start):
    r = hostile(ex1, tmp_path, {"do": "exit", "code": 5})
    assert (r.error_kind, r.error) == ("crash", "the grading process exited with code 5 without sending a result")
    assert list(private_tmp.iterdir()) == []


def test_a_cpu_hog_is_stopped_by_the_cpu_limit_and_named_so(ex1, tmp_path, start):
    r = hostile(ex1, tmp_path, {"do": "cpu-hog"}, Limits(cpu_seconds=1, wall_seconds=30))
    assert (r.error_kind, r.error) == ("time limit", "the submission used more than 1 s of CPU time")


def test_a_wall_clock_hog_is_stopped_by_the_wall_limit_and_named_so(ex1, tmp_path):
    r = hostile(ex1, tmp_path, {"do": "cpu-hog"}, Limits(cpu_seconds=30, wall_seconds=1.5))
    assert (r.error_kind, r.error) == ("time limit", "no result within 1.5 s of wall time")
    assert r.elapsed_s < 5


def test_a_memory_hog_is_a_memory_limit_a_raised_memory_error_is_not(ex1, tmp_path, start):
    r = hostile(ex1, tmp_path, {"do": "memory-hog"}, Limits(memory_mb=600, wall_seconds=30))
    assert (r.error_kind, r.error) == ("memory limit", "the submission ran out of memory (the limit is 600 MB)")
    r = hostile(ex1, tmp_path, {"do": "raise-memory-error"})
    assert (r.error_kind, r.error) == (
        "program error",
        "the program raised MemoryError('pretend to be out of memory'); memory was not short",
    )


@pytest.mark.parametrize(
    ("options", "word"),
    [
        ({"cpu_seconds": -1}, "CPU-time limit"),
        ({"cpu_seconds": 0}, "CPU-time limit"),
        ({"memory_mb": 0}, "memory limit"),
        ({"wall_seconds": -5}, "wall-time limit"),
    ],
)
def test_limits_cannot_be_switched_off(options, word):
    with pytest.raises(ConfigurationError, match=word):
        Limits(**options)


def test_the_portable_path_without_process_groups_grades_and_stops_at_the_wall_limit(ex1, tmp_path, monkeypatch):
    """Windows' path (a result file, the grader's outside watch), forced here on a POSIX system; the
    hostile programs on this path are in tests/grading/test_portable_sandbox.py."""
    import plcsim.grading.sandbox.parent

    monkeypatch.setattr(plcsim.grading.sandbox.parent, "POSIX", False)
    r = grade_sandboxed(ex1, ex1.reference.path)
    assert (r.error_kind, r.passed, r.score) == (None, True, 3.0)
    assert r.warnings[0].startswith("sandbox: portable path (no resource limits, process group, namespaces")
    r = hostile(ex1, tmp_path, {"do": "cpu-hog"}, Limits(cpu_seconds=30, wall_seconds=1.5))
    assert (r.error_kind, r.error) == ("time limit", "no result within 1.5 s of wall time")


def test_a_project_inside_the_temporary_folder_is_readable_the_scratch_beside_it_is_not(tmp_path):
    """A clone under /tmp once made every lazy import of the child fail after the lock-down (every
    sandboxed ``.il`` grade crashed on ``plcsim.frontends.il``): the temporary folder is hidden from a
    root that holds it, never from a root inside it."""
    from plcsim.grading.sandbox import readable as sandbox

    temp = tmp_path / "tmp"
    package = temp / "clone" / "plcsim"
    scratch = temp / "plcsim-grade-other"
    for folder in (package, scratch, tmp_path / "lib"):
        folder.mkdir(parents=True)
    submissions = tmp_path / "class"
    submissions.mkdir()
    granted = sandbox._granted(submissions, frozenset(), temp, frozenset({package, tmp_path}))
    assert str(package) in granted  # the root inside the temporary folder, whole
    assert str(tmp_path / "lib") in granted  # a root holding the temporary folder: its other entries
    assert not any(g == str(temp) or g.startswith(str(scratch)) for g in granted)


@NAMESPACES
def test_a_project_installed_under_the_temporary_folder_grades_an_il_program_in_the_sandbox(tmp_path):
    """End to end, as on a fresh clone in /tmp: a copy of the project imported from inside the temporary
    folder grades a Tecomat program (whose front end is imported only after the lock-down)."""
    import shutil
    import subprocess

    root = Path(__file__).resolve().parents[2]
    temp = tmp_path / "tmp"
    clone = temp / "clone"
    for package in ("plcsim", "plants", "exercises"):
        shutil.copytree(root / package, clone / package, ignore=shutil.ignore_patterns("__pycache__"))
    submission = tmp_path / "mine.il"
    shutil.copy(root / "exercises" / "solutions" / "T_01" / "reference.il", submission)
    script = (
        "import exercises, sys\n"
        "from pathlib import Path\n"
        "from plcsim.grading.grader import grade_sandboxed\n"
        "r = grade_sandboxed(exercises.get('T-01'), Path(sys.argv[1]))\n"
        "print(r.error_kind, r.error, r.score, r.max_score)\n"
    )
    env = {**os.environ, "PYTHONPATH": str(clone), "TMPDIR": str(temp)}
    out = subprocess.run(
        [sys.executable, "-c", script, str(submission)], cwd=tmp_path, env=env, capture_output=True, text=True
    )
    assert out.returncode == 0, out.stderr
    assert out.stdout.split() == ["None", "None", "8.0", "8.0"], out.stdout
