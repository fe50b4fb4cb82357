"""The fork server (plcsim.grading.sandbox.forkserver) as the hostile child sees it: a child forked from it reaches
nothing of the server, changes nothing the next child gets, and a server that dies costs no student
a grade. Linux only (elsewhere every child is a fresh interpreter)."""

from __future__ import annotations

import json
import os
import signal
import subprocess
import sys
import threading
import time
from pathlib import Path

import numpy as np
import pytest

from exercises import get
from plcsim.grading.grader import grade_sandboxed
from plcsim.grading.sandbox import forkserver
from plcsim.grading.sandbox.limits import Limits

pytestmark = [
    pytest.mark.xdist_group("sandbox"),
    pytest.mark.skipif(not forkserver.enabled(), reason="children are forked from a server on Linux only"),
]
HOSTILE = "sandbox_hostile_child"


@pytest.fixture(scope="module")
def ex1():
    return get("4.3.1")


@pytest.fixture(autouse=True)
def no_server_yet():
    """Each test starts with no server in this process, so that it knows which server is its own."""
    forkserver.close_all()


def hostile(ex1, tmp_path, order, limits=None):
    path = tmp_path / f"{order['do']}.py"
    path.write_text(json.dumps(order), encoding="utf-8")
    return grade_sandboxed(ex1, path, child_entry=HOSTILE, limits=limits)


def servers() -> list[forkserver.ForkServer]:
    return [s for s in forkserver._SERVERS.values() if s.alive]


def test_a_forked_child_holds_no_descriptor_but_its_result_pipe_and_the_null_device(ex1, tmp_path):
    r = hostile(ex1, tmp_path, {"do": "descriptors"})
    assert (r.error_kind, r.passed) == (None, True), r.error
    opened = dict(w.removeprefix("open ").split(" -> ") for w in r.warnings)
    assert [opened[fd] for fd in ("0", "1", "2")] == ["/dev/null"] * 3
    others = sorted(target.split(":")[0] for fd, target in opened.items() if fd not in ("0", "1", "2"))
    assert others == ["closed", "pipe"], opened  # the listing's own descriptor, the result pipe: no socket


def test_what_a_child_changes_in_its_memory_never_reaches_the_next_child(ex1, tmp_path):
    r = hostile(ex1, tmp_path, {"do": "poison"})
    assert r.error_kind == "crash"
    (server,) = servers()
    honest = grade_sandboxed(ex1, ex1.reference.path)
    wrong = grade_sandboxed(ex1, ex1.solution("wrong-latch").path)
    assert (honest.error_kind, honest.passed, honest.score) == (None, True, 3.0)
    assert (wrong.error_kind, wrong.passed) == (None, False)
    assert servers() == [server]  # the same server forked all three


def test_a_server_killed_between_grades_is_replaced(ex1):
    grade_sandboxed(ex1, ex1.reference.path)
    (server,) = servers()
    os.kill(server.process.pid, signal.SIGKILL)
    server.process.wait()
    deadline = time.monotonic() + 10  # (the reader thread sees the socket close)
    while server.alive and time.monotonic() < deadline:
        time.sleep(0.01)
    r = grade_sandboxed(ex1, ex1.reference.path)
    assert (r.error_kind, r.passed, r.score) == (None, True, 3.0)
    assert servers() and servers()[0] is not server


def test_a_server_dying_under_a_running_child_is_a_grader_error_and_takes_the_child_with_it(ex1, tmp_path):
    grade_sandboxed(ex1, ex1.reference.path)
    (server,) = servers()
    threading.Timer(1.0, os.kill, (server.process.pid, signal.SIGKILL)).start()
    r = hostile(ex1, tmp_path, {"do": "cpu-hog"}, Limits(cpu_seconds=20, wall_seconds=20))
    assert (r.error_kind, r.passed) == ("grader error", False)
    assert "fork server" in r.error
    assert r.elapsed_s < 10
    deadline = time.monotonic() + 10  # (a loaded machine may take a while to reap them)
    while _named(forkserver.CHILD_NAME) and time.monotonic() < deadline:
        time.sleep(0.02)
    assert not _named(forkserver.CHILD_NAME)


def test_the_server_ends_with_its_grader_and_leaves_no_child(tmp_path):
    script = (
        "import exercises\n"
        "from plcsim.grading.sandbox import forkserver\n"
        "from plcsim.grading.grader import grade_sandboxed\n"
        "ex = exercises.get('4.3.1')\n"
        "r = grade_sandboxed(ex, ex.reference.path)\n"
        "print(r.score, list(forkserver._SERVERS.values())[0].process.pid, flush=True)\n"
    )
    root = Path(__file__).resolve().parents[2]
    out = subprocess.run([sys.executable, "-c", script], cwd=root, capture_output=True, text=True, check=True)
    score, pid = out.stdout.split()
    assert score == "3.0"
    deadline = time.monotonic() + 5
    while _alive(int(pid)) and time.monotonic() < deadline:
        time.sleep(0.02)
    assert not _alive(int(pid))


def test_a_forked_child_gives_the_same_trace_as_a_fresh_one_bit_for_bit(tmp_path, monkeypatch):
    ex = get("4.3.5")
    tables = {}
    for start in ("forked", "fresh"):
        if start == "fresh":
            monkeypatch.setenv(forkserver.VARIABLE, "off")
        r = grade_sandboxed(ex, ex.reference.path, traces_dir=tmp_path / start)
        assert r.passed, r.error
        tables[start] = [dict(np.load(run.trace_npz)) for run in r.runs]
    assert len(tables["forked"]) == len(tables["fresh"]) > 0
    for forked, fresh in zip(tables["forked"], tables["fresh"]):
        assert forked.keys() == fresh.keys()
        for key in forked:
            assert np.array_equal(forked[key], fresh[key]), key


def _alive(pid: int) -> bool:
    try:
        return Path(f"/proc/{pid}/stat").read_text(encoding="utf-8").split(") ")[1][0] != "Z"
    except (FileNotFoundError, IndexError):
        return False


def _named(name: bytes) -> list[int]:
    """The live processes whose ``/proc/PID/comm`` is ``name``, other than this one."""
    found = []
    for entry in os.listdir("/proc"):
        if entry.isdigit() and int(entry) != os.getpid():
            try:
                if Path(f"/proc/{entry}/comm").read_bytes().strip() == name and _alive(int(entry)):
                    found.append(int(entry))
            except OSError:
                continue
    return found


def test_a_grader_forked_after_it_graded_starts_a_server_of_its_own_and_leaves_the_first_alone(ex1):
    assert grade_sandboxed(ex1, ex1.reference.path).passed
    (server,) = servers()
    pid = os.fork()
    if pid == 0:  # the forked grader: its inherited server is not its own
        code = 3
        try:
            mine = grade_sandboxed(ex1, ex1.reference.path)
            code = 0 if mine.passed and servers() and servers()[0] is not server else 1
        finally:
            os._exit(code)
    status, deadline = None, time.monotonic() + 60
    while status is None and time.monotonic() < deadline:
        done, raw = os.waitpid(pid, os.WNOHANG)
        status = os.waitstatus_to_exitcode(raw) if done else time.sleep(0.05)
    if status is None:
        os.kill(pid, signal.SIGKILL)
        os.waitpid(pid, 0)
    assert status == 0
    assert grade_sandboxed(ex1, ex1.reference.path).passed
    assert servers() == [server]
