"""The portable sandbox path (Windows' path), proved on Linux with ``PLCSIM_SANDBOX=portable``: every
Unix-only part is off (resource limits, process group, namespaces, Landlock, cgroups, fork) and the
grader watches the child from outside (plcsim.grading.sandbox.watchdog). The hostile children of the POSIX tests must
still be contained: the forged results refused, the CPU hog, the wall-clock hog, the memory hog and
the huge output stopped and named, nothing left behind.

The tests of tests/grading/test_sandbox_child.py and tests/grading/test_grading.py imported below run here a second
time, on the portable path (the autouse fixture); those that prove a POSIX-only guard (a grandchild
leaving the group, Landlock) are not imported: docs/grading-sandbox.md says what this path lacks.
"""

# ruff: noqa: F811 - the fixtures ex1 and private_tmp are imported, and pytest passes them by name

from __future__ import annotations

import json
import os
import subprocess
import sys
import time

import psutil
import pytest
from test_grading import (  # noqa: F401 - fixtures and tests re-run on the portable path
    ex1,
    test_a_cpu_hog_hits_the_time_limit,
    test_a_good_submission_passes_in_the_sandbox,
    test_a_syntax_error_is_reported_with_its_line,
    test_an_endless_loop_is_stopped_by_the_cycle_watchdog,
    test_grade_batch_with_a_broken_submission,
    test_the_wall_time_limit,
    write,
)
from test_sandbox_child import (  # noqa: F401 - fixtures and tests re-run on the portable path
    private_tmp,
    test_a_cpu_hog_is_stopped_by_the_cpu_limit_and_named_so,
    test_a_forged_message_on_the_pipe_is_an_invalid_result,
    test_a_memory_hog_is_a_memory_limit_a_raised_memory_error_is_not,
    test_a_wall_clock_hog_is_stopped_by_the_wall_limit_and_named_so,
    test_an_exit_without_result_is_a_crash_with_its_exit_code_and_leaves_no_scratch,
    test_forged_passed_lines_on_stdout_and_stderr_count_for_nothing,
    test_the_control_an_honest_trace_of_the_reference_gets_full_marks,
)

from plcsim.core.errors import ConfigurationError
from plcsim.grading.grader import grade_sandboxed
from plcsim.grading.sandbox.confine import ORPHANED_EXIT
from plcsim.grading.sandbox.limits import Limits
from plcsim.grading.sandbox.parent import MODE_VARIABLE, portable_mode

# one xdist worker runs them in turn: they look for the hostile child's leftovers machine-wide and
# time their limits, so two at once on two cores would see each other
pytestmark = pytest.mark.xdist_group("sandbox")

PORTABLE_HOSTILE = "portable_hostile_child"


@pytest.fixture(autouse=True)
def portable(monkeypatch):
    monkeypatch.setenv(MODE_VARIABLE, "portable")


@pytest.fixture
def start():
    """How the imported tests' child starts: afresh (the portable path has no fork server)."""
    return "fresh"


def hostile(ex1, tmp_path, order, limits=None):
    path = tmp_path / "order.py"
    path.write_text(json.dumps(order), encoding="utf-8")
    return grade_sandboxed(ex1, path, child_entry=PORTABLE_HOSTILE, limits=limits)


def test_the_switch_is_on_and_the_report_says_what_the_portable_path_lacks(ex1):
    assert portable_mode()
    r = grade_sandboxed(ex1, ex1.reference.path)
    assert (r.error_kind, r.passed, r.score) == (None, True, 3.0)
    (note,) = [w for w in r.warnings if w.startswith("sandbox:")]
    assert "no resource limits, process group, namespaces or file confinement" in note
    assert "may read and write wherever the grading user may" in note


def test_a_misspelt_mode_is_refused_with_the_variable_named(monkeypatch):
    monkeypatch.setenv(MODE_VARIABLE, "portible")
    with pytest.raises(ConfigurationError, match=r"PLCSIM_SANDBOX='portible' is not a sandbox mode; use 'portable'"):
        portable_mode()


def test_a_result_file_that_grows_without_end_is_stopped_at_the_largest_possible_result(ex1, tmp_path, private_tmp):
    r = hostile(ex1, tmp_path, {"do": "huge-result"}, Limits(wall_seconds=300))
    assert r.error_kind == "invalid result"  # stopped at the cap (some MB); the wall-time limit is a "time limit"
    assert r.error.startswith("the child sent more than ") and r.error.endswith(" bytes")
    assert list(private_tmp.iterdir()) == []


def test_a_flood_on_stdout_is_thrown_away_and_the_honest_result_counts(ex1, tmp_path):
    r = hostile(ex1, tmp_path, {"do": "huge-stdout", "megabytes": 200})
    assert (r.error_kind, r.passed, r.score, r.max_score) == (None, True, 3.0, 3.0)


def test_a_process_the_child_starts_is_killed_with_it(ex1, tmp_path):
    pid_file = tmp_path / "sleeper.pid"
    order = {"do": "spawn-then-hog", "pid_file": str(pid_file)}
    r = hostile(ex1, tmp_path, order, Limits(cpu_seconds=1, wall_seconds=30))
    assert (r.error_kind, r.error) == ("time limit", "the submission used more than 1 s of CPU time")
    assert _dies(int(pid_file.read_text(encoding="utf-8")))


def test_the_cpu_time_of_what_the_child_starts_counts_too(ex1, tmp_path):
    pid_file = tmp_path / "hog.pid"
    order = {"do": "spawn-a-hog-then-sleep", "pid_file": str(pid_file)}
    r = hostile(ex1, tmp_path, order, Limits(cpu_seconds=2, wall_seconds=30))
    assert (r.error_kind, r.error) == ("time limit", "the submission used more than 2 s of CPU time")
    assert r.elapsed_s < 25  # the CPU-time limit, not the wall-time limit
    assert _dies(int(pid_file.read_text(encoding="utf-8")))


def test_a_memory_bomb_in_a_program_is_stopped_at_the_memory_limit(ex1, tmp_path):
    source = "def OB1(t):\n    x = [0]\n    for i in range(40):\n        x = x + x\n    t.LED = t.TLACIDLO\n"
    limits = Limits(memory_mb=700, cpu_seconds=20, wall_seconds=60)
    r = grade_sandboxed(ex1, write(tmp_path, "bomb.py", source), limits=limits)
    assert (r.error_kind, r.error) == ("memory limit", "the submission ran out of memory (the limit is 700 MB)")
    assert (r.passed, r.score, r.max_score) == (False, 0.0, 3.0)


def test_a_child_whose_grader_is_killed_ends_itself(tmp_path):
    """No PR_SET_PDEATHSIG on the portable path: the child ends when the grader's end of its stdin closes."""
    pid_file = tmp_path / "child.pid"
    order = tmp_path / "order.py"
    order.write_text(json.dumps({"do": "tell-pid-then-hog", "pid_file": str(pid_file)}), encoding="utf-8")
    script = (
        "import sys; sys.path[:0] = sys.argv[2:]\n"
        "from exercises import get\nfrom plcsim.grading.grader import grade_sandboxed\n"
        f"grade_sandboxed(get('4.3.1'), sys.argv[1], child_entry={PORTABLE_HOSTILE!r})\n"
    )
    grader = subprocess.Popen(
        [sys.executable, "-c", script, str(order), *sys.path],
        env={**os.environ, MODE_VARIABLE: "portable"},
    )
    try:
        deadline = time.monotonic() + 30
        while not pid_file.exists() or not pid_file.read_text(encoding="utf-8"):
            assert time.monotonic() < deadline, "the child never started"
            time.sleep(0.05)
        child = int(pid_file.read_text(encoding="utf-8"))
        assert _alive(child)
        grader.kill()  # no clean-up runs in the grader: only the closed stdin tells the child
        grader.wait()
        assert _dies(child, within=5)
    finally:
        grader.kill()
        grader.wait()


def _dies(pid: int, within: float = 2) -> bool:
    """True once ``pid`` is gone or a zombie, waiting ``within`` seconds at most (a kill takes effect soon,
    not at once)."""
    deadline = time.monotonic() + within
    while _alive(pid) and time.monotonic() < deadline:
        time.sleep(0.05)
    return not _alive(pid)


def _alive(pid: int) -> bool:
    try:
        return psutil.Process(pid).status() != psutil.STATUS_ZOMBIE
    except psutil.NoSuchProcess:
        return False


@pytest.mark.parametrize(
    ("script", "close_stdin", "code"),
    [
        ("pass", False, 0),  # ends normally while the grader holds stdin: no abort at shutdown
        ("import time; time.sleep(30)", True, ORPHANED_EXIT),  # the grader's end closes: it ends itself
    ],
    ids=["normal-end", "grader-gone"],
)
def test_the_portable_child_s_watch_on_its_grader(script, close_stdin, code):
    child = subprocess.Popen(
        [sys.executable, "-c", f"from plcsim.grading.sandbox import confine; confine.exit_with_grader(); {script}"],
        stdin=subprocess.PIPE,
        stderr=subprocess.PIPE,
    )
    try:
        if close_stdin:
            time.sleep(1)
            child.stdin.close()
        assert child.wait(timeout=20) == code, child.stderr.read().decode()
    finally:
        child.kill()
        child.wait()
