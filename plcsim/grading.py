"""Grade a submission: run it in every scenario of an exercise, evaluate the checks, report.

A submission runs in a child process with CPU-time, memory and wall-time limits; the program
compiler accepts only the PLC subset of Python. Whatever goes wrong (a syntax error, an import, an
endless loop, an exception in a network, a crash of the child) ends up as a report, never as a
crash of the grader.
"""

from __future__ import annotations

import csv
import json
import multiprocessing
import resource
import signal
import time
import traceback
from collections.abc import Callable, Iterable, Sequence
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import Any
from xml.etree import ElementTree as ET

from plcsim.check import StaticCheck, evaluate_all
from plcsim.errors import PlcError, SubsetError
from plcsim.exercise import Exercise, GradedCheck
from plcsim.program import Program


@dataclass
class CheckResult:
    """One check in one scenario."""

    scenario: str
    check: str
    passed: bool
    message: str
    points: float
    max_points: float
    at_ns: int | None = None
    signals: list[str] = field(default_factory=list)
    window: tuple[int, int] | None = None
    diagram: str | None = None


@dataclass
class ScenarioRun:
    """How one scenario ran."""

    scenario: str
    seed: int
    simulated_ns: int
    scans: int
    cpu_mode: str
    cpu_error: str | None = None
    rrd: str | None = None
    trace_npz: str | None = None


@dataclass
class Report:
    """The grade of one submission for one exercise."""

    exercise: str
    title: str
    submission: str
    passed: bool = False
    score: float = 0.0
    max_score: float = 0.0
    checks: list[CheckResult] = field(default_factory=list)
    runs: list[ScenarioRun] = field(default_factory=list)
    error: str | None = None
    error_kind: str | None = None
    warnings: list[str] = field(default_factory=list)
    elapsed_s: float = 0.0

    def to_dict(self) -> dict[str, Any]:
        return asdict(self)

    @classmethod
    def from_dict(cls, data: dict[str, Any]) -> Report:
        data = dict(data)
        data["checks"] = [
            CheckResult(**{**c, "window": tuple(c["window"]) if c.get("window") is not None else None})
            for c in data.get("checks", [])
        ]  # JSON has no tuples: a window comes back as a list
        data["runs"] = [ScenarioRun(**r) for r in data.get("runs", [])]
        return cls(**data)

    def to_json(self, path: str | Path | None = None) -> str:
        text = json.dumps(self.to_dict(), indent=2)
        if path is not None:
            Path(path).write_text(text, encoding="utf-8")
        return text

    def failed(self) -> list[CheckResult]:
        return [c for c in self.checks if not c.passed]

    def result(self, check: str, scenario: str | None = None) -> CheckResult:
        """The result of one check (in one scenario, or the first failing/any scenario)."""
        found = [c for c in self.checks if c.check == check and (scenario is None or c.scenario == scenario)]
        if not found:
            raise KeyError(f"no result for check {check!r}; checks: {sorted({c.check for c in self.checks})}")
        failing = [c for c in found if not c.passed]
        return failing[0] if failing else found[0]

    def to_junit(self, path: str | Path | None = None) -> str:
        suites = ET.Element(
            "testsuites", name=f"plcsim {self.exercise}", tests=str(len(self.checks)), failures=str(len(self.failed()))
        )
        by_scenario: dict[str, list[CheckResult]] = {}
        for c in self.checks:
            by_scenario.setdefault(c.scenario, []).append(c)
        if self.error and not self.checks:
            suite = ET.SubElement(suites, "testsuite", name=self.exercise, tests="1", failures="1")
            case = ET.SubElement(suite, "testcase", name="load", classname=self.exercise)
            ET.SubElement(case, "failure", message=self.error, type=self.error_kind or "error")
        for scenario, results in by_scenario.items():
            suite = ET.SubElement(
                suites,
                "testsuite",
                name=f"{self.exercise}.{scenario}",
                tests=str(len(results)),
                failures=str(sum(not r.passed for r in results)),
            )
            for r in results:
                case = ET.SubElement(suite, "testcase", name=r.check, classname=f"{self.exercise}.{scenario}")
                if not r.passed:
                    failure = ET.SubElement(case, "failure", message=r.message, type="check failed")
                    failure.text = r.message + (f"\ntiming diagram: {r.diagram}" if r.diagram else "")
        text = ET.tostring(suites, encoding="unicode")
        if path is not None:
            Path(path).write_text('<?xml version="1.0" encoding="utf-8"?>\n' + text, encoding="utf-8")
        return text


@dataclass
class Limits:
    """Resource limits of the child process that runs a submission."""

    cpu_seconds: int = 60
    memory_mb: int = 2048
    wall_seconds: float = 120.0


# --------------------------------------------------------------------------------------------
# Grading in this process
# --------------------------------------------------------------------------------------------


def grade(
    exercise: Exercise,
    submission: Program | str | Path,
    *,
    seed: int = 1,
    name: str | None = None,
    scenarios: Sequence[str] | None = None,
    rrd_dir: str | Path | None = None,
    plots_dir: str | Path | None = None,
    traces_dir: str | Path | None = None,
) -> Report:
    """Grade a program in this process (trusted code, tests, notebooks). See :func:`grade_sandboxed`."""
    started = time.perf_counter()
    label = name or (submission.filename if isinstance(submission, Program) else str(submission))
    report = Report(exercise.number, exercise.title, label)
    try:
        program = submission if isinstance(submission, Program) else Program.from_file(submission)
    except PlcError as exc:
        return _load_failure(report, exc, exercise, started)
    chosen = [s for s in exercise.scenarios if scenarios is None or s.name in scenarios]
    static_done = False
    for scenario in chosen:
        try:
            sim = exercise.simulation(program, scenario, seed=seed)
        except PlcError as exc:
            return _load_failure(report, exc, exercise, started)
        if not report.warnings:
            report.warnings = list(sim.cpu.warnings)
        error = None
        try:
            sim.run()
        except PlcError as exc:  # a plant failure: the trace so far is graded
            error = str(exc)
        cpu_error = sim.cpu.error
        run = ScenarioRun(
            scenario.name, seed, sim.now, sim.cpu.scan_count, sim.cpu.mode, str(cpu_error) if cpu_error else error
        )
        stem = f"{exercise.slug}-{scenario.name.replace(' ', '_')}"
        if rrd_dir is not None:
            run.rrd = str(_save_rrd(sim, Path(rrd_dir) / f"{stem}.rrd"))
        if traces_dir is not None:
            run.trace_npz = str(sim.trace.save(Path(traces_dir) / f"{stem}.npz"))
        report.runs.append(run)
        graded: list[GradedCheck] = []
        for gc in exercise.checks_for(scenario.name):
            if isinstance(gc.check, StaticCheck):
                if static_done:
                    continue
                graded.append(gc)
            else:
                graded.append(gc)
        analysis = sim.cpu.compiled.analysis if sim.cpu.compiled else None
        for gc, (_, verdict) in zip(graded, evaluate_all([g.check for g in graded], sim.trace, analysis)):
            where = "static" if isinstance(gc.check, StaticCheck) else scenario.name
            weight = gc.check.weight
            message = verdict.message
            if not verdict.passed and run.cpu_error and where != "static":
                message += f" [the CPU stopped: {run.cpu_error}]"
            result = CheckResult(
                where,
                gc.name,
                verdict.passed,
                message,
                weight if verdict.passed else 0.0,
                weight,
                verdict.at_ns,
                verdict.signals,
                verdict.window,
            )
            if not verdict.passed and plots_dir is not None and where != "static":
                result.diagram = _diagram(sim, result, Path(plots_dir) / f"{stem}-{_slug(gc.name)}.png")
            report.checks.append(result)
        static_done = True
    report.score = sum(c.points for c in report.checks)
    report.max_score = sum(c.max_points for c in report.checks)
    report.passed = bool(report.checks) and all(c.passed for c in report.checks) and report.error is None
    report.elapsed_s = time.perf_counter() - started
    return report


def max_score(exercise: Exercise) -> float:
    """The points of an exercise: each check's weight once per scenario it applies to (static checks once)."""
    return sum(
        c.check.weight * (1 if isinstance(c.check, StaticCheck) else len(c.scenarios or exercise.scenarios))
        for c in exercise.checks
    )


def _load_failure(report: Report, exc: PlcError, exercise: Exercise, started: float) -> Report:
    report.error = str(exc)
    report.error_kind = "subset violation" if isinstance(exc, SubsetError) else "program error"
    report.max_score = max_score(exercise)
    report.elapsed_s = time.perf_counter() - started
    return report


def _slug(text: str) -> str:
    return "".join(ch if ch.isalnum() else "_" for ch in text)[:60].strip("_")


def _save_rrd(sim: Any, path: Path) -> Path:
    path.parent.mkdir(parents=True, exist_ok=True)
    return sim.trace.to_rrd(path)


def _diagram(sim: Any, result: CheckResult, path: Path) -> str | None:
    try:
        from plcsim.trace_plot import save_timing_diagram
    except ImportError:
        return None
    path.parent.mkdir(parents=True, exist_ok=True)
    signals = [s for s in result.signals if s in sim.trace] or None
    start = end = None
    if result.window is not None:
        first = min(result.window[0], result.at_ns if result.at_ns is not None else result.window[0])
        margin = max(1_000_000_000, (result.window[1] - first) // 4)
        start = max(0, first - margin)
        end = result.window[1] + margin
    highlight = (result.window[0], result.window[1], result.check) if result.window else None
    save_timing_diagram(
        sim.trace, path, signals, start=start, end=end, highlight=highlight, title=f"{result.scenario}: {result.check}"
    )
    return str(path)


# --------------------------------------------------------------------------------------------
# Grading in a child process
# --------------------------------------------------------------------------------------------


def _child(conn: Any, exercise: Exercise, path: str, seed: int, limits: Limits, options: dict[str, Any]) -> None:
    try:
        resource.setrlimit(resource.RLIMIT_CPU, (limits.cpu_seconds, limits.cpu_seconds + 5))
        mem = limits.memory_mb * 1024 * 1024
        resource.setrlimit(resource.RLIMIT_AS, (mem, mem))
    except (ValueError, OSError):  # pragma: no cover - some systems refuse; grading still runs
        pass
    try:
        report = grade(exercise, path, seed=seed, **options)
        conn.send(report.to_dict())
    except MemoryError:
        conn.send({"__error__": "memory limit", "message": f"the submission used more than {limits.memory_mb} MB"})
    except BaseException as exc:  # noqa: BLE001 - everything is reported to the parent
        conn.send(
            {
                "__error__": "grader error",
                "message": f"{type(exc).__name__}: {exc}",
                "trace": traceback.format_exc(limit=5),
            }
        )
    finally:
        conn.close()


def grade_sandboxed(
    exercise: Exercise, path: str | Path, *, seed: int = 1, limits: Limits | None = None, **options: Any
) -> Report:
    """Grade an untrusted submission file in a child process with CPU, memory and wall-time limits."""
    limits = limits or Limits()
    started = time.perf_counter()
    ctx = multiprocessing.get_context("fork")  # the child inherits the exercise; nothing is pickled
    parent, child = ctx.Pipe(duplex=False)
    proc = ctx.Process(target=_child, args=(child, exercise, str(path), seed, limits, options), daemon=True)
    proc.start()
    child.close()
    data = None
    out_of_time = False
    if parent.poll(limits.wall_seconds):
        try:
            data = parent.recv()
        except EOFError:
            data = None
    elif proc.is_alive():  # the wall-time limit: stop the child now, not after another wait
        out_of_time = True
        proc.kill()
    proc.join(timeout=5)
    if proc.is_alive():
        proc.kill()
        proc.join()
    report = Report(exercise.number, exercise.title, str(path))
    if isinstance(data, dict) and "__error__" not in data:
        report = Report.from_dict(data)
    elif isinstance(data, dict):
        report.error, report.error_kind = data["message"], data["__error__"]
    elif out_of_time:
        report.error_kind = "time limit"
        report.error = f"no result within {limits.wall_seconds:.0f} s of wall time"
    elif proc.exitcode is not None and proc.exitcode < 0:
        sig = -proc.exitcode
        if sig == signal.SIGXCPU:
            report.error_kind = "time limit"
            report.error = f"the submission used more than {limits.cpu_seconds} s of CPU time"
        else:
            report.error_kind = "crash"
            report.error = f"the grading process was killed by signal {signal.Signals(sig).name}"
    else:
        report.error_kind = "time limit"
        report.error = f"no result within {limits.wall_seconds:.0f} s of wall time"
    if report.error and not report.max_score:
        report.max_score = max_score(exercise)
    report.elapsed_s = time.perf_counter() - started
    return report


def grade_batch(
    exercise: Exercise,
    paths: Iterable[str | Path],
    *,
    jobs: int = 1,
    seed: int = 1,
    limits: Limits | None = None,
    progress: Callable[[int, int, Report], None] | None = None,
    **options: Any,
) -> list[Report]:
    """Grade many submissions, ``jobs`` at a time, each in its own child process."""
    from concurrent.futures import ThreadPoolExecutor

    paths = [Path(p) for p in paths]
    reports: list[Report | None] = [None] * len(paths)
    done = 0

    def one(k: int) -> tuple[int, Report]:
        return k, grade_sandboxed(exercise, paths[k], seed=seed, limits=limits, **options)

    with ThreadPoolExecutor(max_workers=max(1, jobs)) as pool:
        for k, report in pool.map(one, range(len(paths))):
            reports[k] = report
            done += 1
            if progress is not None:
                progress(done, len(paths), report)
    return [r for r in reports if r is not None]


def write_gradebook(reports: Sequence[Report], path: str | Path) -> Path:
    """A CSV with one row per submission: score, max, passed, error, and each check's result."""
    checks: list[str] = []
    for r in reports:
        for c in r.checks:
            key = f"{c.scenario}: {c.check}"
            if key not in checks:
                checks.append(key)
    path = Path(path)
    with path.open("w", newline="", encoding="utf-8") as f:
        writer = csv.writer(f)
        writer.writerow(["submission", "score", "max_score", "percent", "passed", "error", *checks])
        for r in reports:
            results = {f"{c.scenario}: {c.check}": ("pass" if c.passed else "FAIL") for c in r.checks}
            percent = f"{100 * r.score / r.max_score:.1f}" if r.max_score else "0.0"
            writer.writerow(
                [
                    Path(r.submission).name,
                    f"{r.score:g}",
                    f"{r.max_score:g}",
                    percent,
                    "yes" if r.passed else "no",
                    r.error or "",
                    *(results.get(c, "-") for c in checks),
                ]
            )
    return path
