"""Class-scale grading (plcsim.grading.executors, plcsim.grading.batch.grade_batch): a Dask cluster of two local
worker processes grades a class folder into the same gradebook, JSON reports and JUnit file as
``--jobs 2``, each submission still in its own confined child; a worker killed mid-grade voids that
one grade as a grader error and keeps the others; nothing in batch grading calls ``os.fork``.
"""

from __future__ import annotations

import csv
import os
import re
import shutil
import signal
import tempfile
from pathlib import Path

import pytest
from platforms import SIGNALS

from exercises import get
from plcsim.apps.cli import EXIT_FAILED, EXIT_GRADER, EXIT_USAGE, main
from plcsim.core.errors import ConfigurationError
from plcsim.grading.batch import grade_batch
from plcsim.grading.executors import open_executor
from plcsim.grading.report import write_gradebook, write_junit
from plcsim.grading.sandbox.limits import Limits

# one xdist worker runs them: they share one local Dask cluster (a second would double the workers)
pytestmark = pytest.mark.xdist_group("cluster")

distributed = pytest.importorskip("distributed")

LOOPS = "def OB1(t):\n    t.LED = t.TLACIDLO\n    while True:\n        pass\n"  # the cycle watchdog stops it
BOMB = "def OB1(t):\n    x = [0]\n    for i in range(40):\n        x = x + x\n    t.LED = t.TLACIDLO\n"
HOG = "def OB1(t):\n    x = 0\n    for i in range(300000):\n        x = x + i\n    t.LED = t.TLACIDLO\n"
MEMORY_MB = 1024  # the bomb's allocation fails inside the network: a CPU STOP with a MemoryError, every time


def class_folder(root: Path, number: str, extra: dict[str, str]) -> Path:
    """A folder of submissions: the reference and the wrong solutions of the exercise, and the ``extra`` sources."""
    folder = root / number.replace(".", "_")
    folder.mkdir()
    for sol in get(number).solutions:
        if sol.kind != "alternative":
            shutil.copy(sol.path, folder / f"{sol.name}.py")
    for name, source in extra.items():
        (folder / name).write_text(source, encoding="utf-8")
    return folder


@pytest.fixture(scope="module")
def classes(tmp_path_factory):
    root = tmp_path_factory.mktemp("class")
    led = class_folder(root, "4.3.1", {"loops.py": LOOPS, "bomb.py": BOMB, "imports.py": "import os\n"})
    on_off = class_folder(root, "4.3.4", {"syntax.py": "def OB1(t):\n    if t.S1\n        pass\n"})
    return {"4.3.1": led, "4.3.4": on_off}


def _forbid_fork() -> None:
    """Make ``os.fork`` raise in this process (a thread-unsafe fork would void the grade)."""

    def refuse(*_):
        raise AssertionError("batch grading called os.fork")

    os.fork = refuse


@pytest.fixture(scope="module")
def cluster():
    """``--executor dask --jobs 2``: two spawned worker processes, one thread each (a task whose worker
    dies is not retried here, so that a test can kill one); its client, for the tests to look inside."""
    import dask

    with dask.config.set({"distributed.scheduler.allowed-failures": 0}), open_executor("dask", jobs=2):
        client = distributed.default_client()
        assert dask.config.get("distributed.worker.multiprocessing-method") == "spawn"
        assert [w["nthreads"] for w in client.scheduler_info()["workers"].values()] == [1, 1]
        client.run(_forbid_fork)
        yield client


def without_timings(text: str) -> str:
    text = re.sub(r'"elapsed_s": [0-9.e-]+', '"elapsed_s": _', text)
    return re.sub(r'time="[0-9.]+"', 'time="_"', text)


def outputs(folder: Path) -> dict[str, str]:
    return {str(p.relative_to(folder)): without_timings(p.read_text(encoding="utf-8")) for p in folder.rglob("*.*")}


def test_the_cli_grades_a_class_on_a_local_dask_cluster_like_jobs_2(classes, cluster, tmp_path):
    results = {}
    address = cluster.scheduler.address.replace("tcp://", "dask://")
    for name, how in (("local", ["--jobs", "2"]), ("dask", ["--executor", address])):
        out = tmp_path / name
        reports = ["--gradebook", str(out / "grades.csv"), "--json", str(out / "json"), "--junit", str(out / "all.xml")]
        code = main(["grade", "4.3.1", str(classes["4.3.1"]), *how, "--memory-mb", str(MEMORY_MB), *reports])
        assert code == EXIT_FAILED  # some students failed; no grade is void
        results[name] = outputs(out)
    local, dask = results["local"], results["dask"]
    assert (
        sorted(local)
        == sorted(dask)
        == sorted(["grades.csv", "all.xml"] + [f"json/{p.stem}.json" for p in classes["4.3.1"].glob("*.py")])
    )
    assert local == dask  # byte for byte, but for the timings
    rows = [(r[0], r[1], r[4], r[5][:40], r[6][:50]) for r in csv.reader(local["grades.csv"].splitlines()[1:])]
    assert rows == [
        ("bomb.py", "0", "no", "", "STOP in presses: 0 ns: error in the program [OB1 n"),
        ("imports.py", "0", "no", "subset violation: " + str(classes["4.3.1"])[:22], "-"),
        ("loops.py", "0", "no", "", "STOP in presses: 0 ns: cycle time monitoring excee"),
        ("reference.py", "3", "yes", "", "RUN"),
        ("wrong-latch.py", "0", "no", "", "RUN"),
    ]
    assert "MemoryError" in local["grades.csv"]


def test_a_cluster_executor_gives_the_same_reports_as_local_threads(classes, cluster, tmp_path, monkeypatch):
    ex = get("4.3.4")
    files = sorted(classes["4.3.4"].glob("*.py"))
    monkeypatch.setattr(os, "fork", lambda: pytest.fail("batch grading called os.fork"), raising=False)  # Windows: none
    books = {}
    for name, executor in (("local", "local"), ("cluster", cluster.get_executor(pure=False))):
        reports = grade_batch(ex, files, jobs=2, executor=executor)
        out = tmp_path / name
        out.mkdir()
        write_gradebook(reports, out / "grades.csv")
        write_junit(reports, out / "all.xml")
        for r in reports:
            r.to_json(out / f"{r.student}.json")
        books[name] = outputs(out)
        assert [(r.student, r.score, r.error_kind) for r in reports] == [
            ("reference", 10.0, None),
            ("syntax", 0.0, "program error"),
            ("wrong-set-reset", 8.0, None),
            ("wrong-start-dominant", 7.0, None),
        ]
    assert books["local"] == books["cluster"]


@SIGNALS
def test_a_worker_killed_mid_grade_voids_that_grade_alone(classes, cluster, tmp_path):
    ex = get("4.3.1")
    hog = tmp_path / "hog.py"
    hog.write_text(HOG, encoding="utf-8")
    files = [hog, classes["4.3.1"] / "reference.py"]
    killed = []

    def kill_the_busy_worker(done, total, report):
        """Once the reference is graded, the hog is the only task left: kill the worker running it."""
        if killed:
            return
        assert report.student == "reference"
        busy = [w for w, keys in cluster.processing().items() if keys]
        assert len(busy) == 1, cluster.processing()
        pid = cluster.run(os.getpid, workers=busy)[busy[0]]
        os.kill(pid, signal.SIGKILL)
        killed.append(pid)

    limits = Limits(cpu_seconds=8, wall_seconds=60)  # the orphaned child of the killed worker ends soon
    reports = grade_batch(
        ex, files, executor=cluster.get_executor(pure=False), limits=limits, progress=kill_the_busy_worker
    )
    assert len(killed) == 1
    dead, good = reports
    assert (good.passed, good.score, good.error) == (True, 3.0, None)
    assert (dead.error_kind, dead.grader_failed, dead.score, dead.max_score) == ("grader error", True, 0.0, 3.0)
    assert dead.error.startswith("the grading task failed (KilledWorker: ")
    assert dead.error.endswith("(a fault of the grader or its workers, not of the submission)")
    cluster.wait_for_workers(2, timeout=60)  # the nanny restarts it
    folders = set(cluster.run(tempfile.gettempdir).values())  # where the killed worker's child had its scratch
    assert len(folders) == 1 and Path(folders.pop()).name.startswith("plcsim-dask-")  # removed with the cluster


def test_an_exercise_no_module_defines_cannot_be_shipped_to_a_worker(cluster):
    import dataclasses

    ex = dataclasses.replace(get("4.3.1"), title="built in a notebook")
    with pytest.raises(ConfigurationError, match="is not importable by a module name"):
        grade_batch(ex, [ex.reference.path], executor=cluster.get_executor(pure=False))


def test_executor_names_and_jobs_are_checked(capsys, classes):
    with pytest.raises(SystemExit) as refused:  # by the argument parser, before anything is graded
        main(["grade", "4.3.1", str(classes["4.3.1"]), "--executor", "ray"])
    assert refused.value.code == EXIT_USAGE
    assert "unknown executor 'ray': use local, dask, or dask://HOST:PORT" in capsys.readouterr().err
    with pytest.raises(ConfigurationError, match="--jobs must be a whole number of at least 1, got 0"):
        open_executor("local", jobs=0).__enter__()


def test_an_existing_scheduler_is_reached_by_its_address_and_its_workers_versions_are_checked(cluster, monkeypatch):
    import plcsim.core.version

    ex = get("4.3.1")
    address = cluster.scheduler.address  # tcp://127.0.0.1:PORT
    (report,) = grade_batch(ex, [ex.reference.path], executor=address.replace("tcp://", "dask://"))
    assert (report.passed, report.score) == (True, 3.0)
    monkeypatch.setattr(plcsim.core.version, "__version__", "0.0.0-other")
    with pytest.raises(
        ConfigurationError, match=r"the Dask workers tcp://127\.0\.0\.1:\d+, tcp://127\.0\.0\.1:\d+ run"
    ):
        grade_batch(ex, [ex.reference.path], executor=address)


def test_a_scheduler_that_does_not_answer_and_a_missing_dask_are_usage_errors(monkeypatch):
    import socket
    import sys

    from plcsim.grading import executors

    with socket.socket() as s:  # a port nobody listens on
        s.bind(("127.0.0.1", 0))
        port = s.getsockname()[1]
    monkeypatch.setattr(executors, "CONNECT_TIMEOUT_S", 2)
    with pytest.raises(ConfigurationError, match=f"cannot reach the Dask scheduler at tcp://127.0.0.1:{port}: "):
        open_executor(f"tcp://127.0.0.1:{port}").__enter__()
    monkeypatch.setitem(sys.modules, "distributed", None)  # import distributed raises ImportError
    with pytest.raises(ConfigurationError, match=r"needs Dask distributed: pip install 'plcsim\[cluster\]'"):
        open_executor("dask").__enter__()


def test_a_task_that_raises_is_a_grader_error_of_that_submission_alone(classes, monkeypatch):
    from plcsim.grading import batch as grading

    real = grading.grade_sandboxed

    def flaky(exercise, path, **options):
        if Path(path).name == "wrong-set-reset.py":
            raise OSError("No space left on device")
        return real(exercise, path, **options)

    monkeypatch.setattr(grading, "grade_sandboxed", flaky)
    reports = grade_batch(get("4.3.4"), sorted(classes["4.3.4"].glob("*.py")), jobs=2)
    assert [(r.student, r.score, r.error_kind) for r in reports] == [
        ("reference", 10.0, None),
        ("syntax", 0.0, "program error"),
        ("wrong-set-reset", 0.0, "grader error"),
        ("wrong-start-dominant", 7.0, None),
    ]
    assert reports[2].error.startswith("the grading task failed (OSError: No space left on device); ")
    assert main(["grade", "4.3.4", str(classes["4.3.4"]), "--jobs", "2"]) == EXIT_GRADER
