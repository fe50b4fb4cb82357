"""Grade a submission: run it in every scenario of an exercise, evaluate the checks, report.

Grading has two halves that both paths share: :func:`run_scenarios` runs the program and returns
raw results (traces, CPU state; no score), :func:`evaluate` runs the exercise's checks on them and
builds the :class:`Report`. :func:`grade` does both in this process (trusted code: tests,
notebooks). :func:`grade_sandboxed` runs the first half in a confined child process
(:mod:`plcsim.grading.sandbox.parent`) and the second here, on results validated by :mod:`plcsim.grading.run_result`: what
the child sends can lose points, never earn them. Exporters (rerun recordings, timing diagrams,
``.npz`` traces) run here too, from the returned traces, so a grade never depends on which files
were asked for.
"""

from __future__ import annotations

import contextlib
import importlib
import sys
import time
from collections.abc import Callable, Iterable, Sequence
from concurrent.futures import Executor, Future, ThreadPoolExecutor, as_completed
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from plcsim.check import StaticCheck
from plcsim.check.base import Context
from plcsim.check.exercised import Activity, scenario_writes, unprovoked
from plcsim.controllers.loaded import SourceProgram
from plcsim.core import version
from plcsim.core.errors import ConfigurationError, PlcError, SubsetError
from plcsim.core.literals import format_ns
from plcsim.exercise.model import Exercise
from plcsim.frontends import read_program
from plcsim.frontends.python.program import Program
from plcsim.grading.report import NOT_EXERCISED, CheckResult, Report, ScenarioRun, write_gradebook, write_junit
from plcsim.grading.run_result import RunResult

__all__ = [
    "CheckResult",
    "Limits",
    "Report",
    "ScenarioRun",
    "evaluate",
    "grade",
    "grade_batch",
    "grade_sandboxed",
    "load_error_kind",
    "max_score",
    "run_scenarios",
    "write_gradebook",
    "write_junit",
]


@dataclass
class Limits:
    """Resource limits of the child process that runs a submission; each must be positive.

    >>> Limits(cpu_seconds=-1)
    Traceback (most recent call last):
    ...
    plcsim.core.errors.ConfigurationError: the CPU-time limit must be a positive whole number of seconds, got -1 ...
    """

    cpu_seconds: int = 60
    memory_mb: int = 2048
    wall_seconds: float = 120.0

    def __post_init__(self) -> None:
        if isinstance(self.cpu_seconds, bool) or not isinstance(self.cpu_seconds, int) or self.cpu_seconds < 1:
            raise ConfigurationError(
                f"the CPU-time limit must be a positive whole number of seconds, got {self.cpu_seconds!r} "
                f"(--cpu-seconds 60); a limit cannot be switched off"
            )
        if isinstance(self.memory_mb, bool) or not isinstance(self.memory_mb, int) or self.memory_mb < 64:
            raise ConfigurationError(
                f"the memory limit must be a whole number of at least 64 MB, got {self.memory_mb!r} (--memory-mb 2048)"
            )
        if not isinstance(self.wall_seconds, int | float) or not self.wall_seconds > 0:
            raise ConfigurationError(
                f"the wall-time limit must be a positive number of seconds, got {self.wall_seconds!r}"
            )


# --------------------------------------------------------------------------------------------
# The two halves: running and evaluating
# --------------------------------------------------------------------------------------------


def load_error_kind(exc: PlcError) -> str:
    """The outcome kind of a program that could not be loaded: a configuration error (an exercise's
    scenario, wiring or CPU option; an instructor's mistake) is the grader's, not the student's."""
    if isinstance(exc, SubsetError):
        return "subset violation"
    return "grader error" if isinstance(exc, ConfigurationError) else "program error"


def chosen_scenarios(exercise: Exercise, scenarios: Sequence[str] | None) -> list[Any]:
    """The exercise's scenarios to grade (all, or those named), in the exercise's order."""
    return [s for s in exercise.scenarios if scenarios is None or s.name in scenarios]


def run_scenarios(
    exercise: Exercise, program: Program, *, seed: int, scenarios: Sequence[str] | None = None
) -> tuple[list[RunResult], Any]:
    """Run ``program`` in each chosen scenario: the raw results and the program's static analysis.

    Raises PlcError if the program cannot be loaded on the exercise's CPU."""
    results, analysis = [], None
    for scenario in chosen_scenarios(exercise, scenarios):
        sim = exercise.simulation(program, scenario, seed=seed)
        if analysis is None and sim.cpu.compiled is not None:
            analysis = sim.cpu.compiled.analysis
        plant_error = None
        try:
            sim.run()
        except ConfigurationError:  # the exercise's mistake (ExerciseError): the grader's, not a plant failure
            raise
        except PlcError as exc:  # a plant failure: the run ends early (see :func:`evaluate`)
            plant_error = str(exc)
        cpu = sim.cpu
        results.append(
            RunResult(
                scenario.name,
                seed,
                sim.trace,
                sim.now,
                cpu.scan_count,
                cpu.mode,
                str(cpu.error) if cpu.error else None,
                plant_error,
                list(cpu.warnings),
            )
        )
    return results, analysis


class GraderError(Exception):
    """A check of the exercise failed to evaluate: the instructor's or the grader's bug."""


def evaluate(exercise: Exercise, runs: Sequence[RunResult], analysis: Any, report: Report) -> Report:
    """Evaluate the exercise's checks on the runs (static checks once, on ``analysis``) into ``report``.

    A run that ended before its scenario did fails its run-time checks: a partial trace proves nothing.
    A check that holds only because the program never drove what it guards is *not exercised*
    (:mod:`plcsim.check.exercised`): 0 points. A check that raises is a grader error (its own outcome),
    never a point lost by the student.
    """
    durations = {s.name: s.duration_ns for s in exercise.scenarios}
    graded = [exercise.scenario(run.scenario) for run in runs]
    activity = Activity.of((run.trace for run in runs), written_by_scenario=scenario_writes(graded))
    if runs and not activity.driven:
        report.warnings.append(
            "the program drove no output or tag in any scenario (it did nothing, or its CPU stopped at once): "
            "no check earns points"
        )
    contexts = [Context.of(run.trace, analysis) for run in runs]
    static_done = False
    try:
        for run, ctx in zip(runs, contexts, strict=True):
            report.runs.append(
                ScenarioRun(
                    run.scenario, run.seed, run.simulated_ns, run.scans, run.cpu_mode, run.cpu_error or run.plant_error
                )
            )
            cut_short = run.simulated_ns < durations[run.scenario]
            for gc in exercise.checks_for(run.scenario):
                static = isinstance(gc.check, StaticCheck)
                if static and static_done:
                    continue
                result = _check(gc, ctx, run, static, cut_short, durations[run.scenario])
                if result.passed:
                    why = activity.unexercised(gc.check) or _unprovoked(gc.check, [ctx] if not static else contexts)
                    if why:
                        result = _not_exercised(result, why, run, static)
                report.checks.append(result)
            static_done = True
    except GraderError as exc:
        report.error, report.error_kind = str(exc), "grader error"
    report.max_score = max_score(exercise) if report.error else sum(c.max_points for c in report.checks)
    report.score = 0.0 if report.error else sum(c.points for c in report.checks)
    report.passed = bool(report.checks) and all(c.passed for c in report.checks) and report.error is None
    return report


def _unprovoked(check: Any, contexts: Sequence[Context]) -> str | None:
    """Why the check's ``exercised_by`` condition happened in none of ``contexts`` (None: it did somewhere)."""
    reasons = [unprovoked(check, ctx) for ctx in contexts]
    return None if any(r is None for r in reasons) else reasons[0]


def _not_exercised(result: CheckResult, why: str, run: RunResult, static: bool) -> CheckResult:
    stopped = f" [the CPU stopped: {run.cpu_error}]" if run.cpu_error and not static else ""
    result.message = f"not exercised: {why}, so its pass shows nothing (the check said: {result.message}){stopped}"
    result.passed, result.points, result.status = False, 0.0, NOT_EXERCISED
    return result


def _check(gc: Any, ctx: Context, run: RunResult, static: bool, cut_short: bool, duration_ns: int) -> CheckResult:
    weight = gc.check.weight
    if cut_short and not static:
        why = run.plant_error or run.cpu_error or "no reason given"
        message = f"the run ended at {format_ns(run.simulated_ns)} of {format_ns(duration_ns)} ({why}); not checked"
        return CheckResult(run.scenario, gc.name, False, message, 0.0, weight)
    try:
        verdict = gc.check.evaluate(ctx)
    except Exception as exc:  # the exercise's bug, reported as such
        raise GraderError(
            f"the check {gc.name!r} of exercise scenario {run.scenario!r} raised {type(exc).__name__}: {exc}; "
            f"this is a fault of the exercise or the grader, not of the submission"
        ) from exc
    signals = list(verdict.signals) + [s for s in gc.check.extra_signals if s not in verdict.signals]
    message = verdict.message
    if not verdict.passed and run.cpu_error and not static:
        message += f" [the CPU stopped: {run.cpu_error}]"
    return CheckResult(
        "static" if static else run.scenario,
        gc.name,
        bool(verdict.passed),
        message,
        weight if verdict.passed else 0.0,
        weight,
        verdict.at_ns,
        signals,
        verdict.window,
    )


def max_score(exercise: Exercise) -> float:
    """The points of an exercise: each check's weight once per scenario it applies to (static checks once)."""
    return sum(
        c.check.weight * (1 if isinstance(c.check, StaticCheck) else len(c.scenarios or exercise.scenarios))
        for c in exercise.checks
    )


def failure_report(report: Report, kind: str, message: str, exercise: Exercise) -> Report:
    """``report`` as the outcome ``kind`` of a submission that earned nothing."""
    report.error, report.error_kind = message, kind
    report.max_score = max_score(exercise)
    return report


# --------------------------------------------------------------------------------------------
# Grading in this process
# --------------------------------------------------------------------------------------------


def grade(
    exercise: Exercise,
    submission: SourceProgram | str | Path,
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
    from_file = isinstance(submission, str | Path)
    label = name or (str(submission) if from_file else getattr(submission, "filename", repr(submission)))
    report = Report(exercise.number, exercise.title, label, seed=seed)
    try:
        program = read_program(submission) if from_file else submission
        runs, analysis = run_scenarios(exercise, program, seed=seed, scenarios=scenarios)
    except PlcError as exc:
        failure_report(report, load_error_kind(exc), str(exc), exercise)
    else:
        report.warnings = list(runs[0].warnings) if runs else []
        evaluate(exercise, runs, analysis, report)
        export(exercise, runs, report, rrd_dir=rrd_dir, plots_dir=plots_dir, traces_dir=traces_dir)
    return _finish(report, started)


# --------------------------------------------------------------------------------------------
# Exporting, from the traces, in the grader
# --------------------------------------------------------------------------------------------


def export(
    exercise: Exercise,
    runs: Sequence[RunResult],
    report: Report,
    *,
    rrd_dir: str | Path | None = None,
    plots_dir: str | Path | None = None,
    traces_dir: str | Path | None = None,
) -> None:
    """Write the recordings, traces and failure diagrams asked for; file names carry the exercise, the
    submission and the scenario, so that the students of a batch never overwrite each other's files."""
    by_name = {run.scenario: run for run in runs}
    for scenario_run in report.runs:
        run = by_name[scenario_run.scenario]
        stem = f"{exercise.slug}-{_slug(report.student)}-{_slug(run.scenario)}"
        if rrd_dir is not None:
            Path(rrd_dir).mkdir(parents=True, exist_ok=True)
            scenario_run.rrd = str(run.trace.to_rrd(Path(rrd_dir) / f"{stem}.rrd"))
        if traces_dir is not None:
            Path(traces_dir).mkdir(parents=True, exist_ok=True)
            scenario_run.trace_npz = str(run.trace.save(Path(traces_dir) / f"{stem}.npz"))
        if plots_dir is not None:
            for result in report.checks:
                if not result.passed and result.scenario == run.scenario and len(run.trace):
                    result.diagram = _diagram(run, result, Path(plots_dir) / f"{stem}-{_slug(result.check)}.png")


def _slug(text: str) -> str:
    return "".join(ch if ch.isalnum() else "_" for ch in text)[:60].strip("_")


def _diagram(run: RunResult, result: CheckResult, path: Path) -> str | None:
    try:
        from plcsim.trace.plot import save_timing_diagram
    except ImportError:
        return None
    path.parent.mkdir(parents=True, exist_ok=True)
    signals = [s for s in result.signals if s in run.trace] or None
    start = end = None
    if result.window is not None:
        first = min(result.window[0], result.at_ns if result.at_ns is not None else result.window[0])
        margin = max(1_000_000_000, (result.window[1] - first) // 4)
        start = max(0, first - margin)
        end = result.window[1] + margin
    highlight = (result.window[0], result.window[1], result.check) if result.window else None
    save_timing_diagram(
        run.trace, path, signals, start=start, end=end, highlight=highlight, title=f"{result.scenario}: {result.check}"
    )
    return str(path)


# --------------------------------------------------------------------------------------------
# Grading in a child process
# --------------------------------------------------------------------------------------------


def grade_sandboxed(
    exercise: Exercise,
    path: str | Path,
    *,
    seed: int = 1,
    limits: Limits | None = None,
    scenarios: Sequence[str] | None = None,
    rrd_dir: str | Path | None = None,
    plots_dir: str | Path | None = None,
    traces_dir: str | Path | None = None,
    child_entry: str | None = None,
    probes: Any = None,
) -> Report:
    """Grade an untrusted submission file: run it in a confined child (:mod:`plcsim.grading.sandbox.parent`), check here.

    ``child_entry`` (tests only) names another child module to start, to prove what the grader does
    with a hostile child's output. ``probes``: a batch's :class:`plcsim.grading.sandbox.probes.Probes`."""
    from plcsim.grading.sandbox.parent import DEFAULT_ENTRY, run_child

    limits = limits or Limits()
    started = time.perf_counter()
    report = Report(exercise.number, exercise.title, str(path), seed=seed)
    try:
        outcome = run_child(
            exercise,
            Path(path),
            seed,
            chosen_scenarios(exercise, scenarios),
            limits,
            geometry=rrd_dir is not None,
            entry=child_entry or DEFAULT_ENTRY,
            probes=probes,
        )
    except Exception as exc:  # noqa: BLE001 - the grader could not run the child: its fault, not the student's
        return _finish(failure_report(report, "grader error", f"{type(exc).__name__}: {exc}", exercise), started)
    report.warnings = list(outcome.notes)
    if outcome.kind is not None:
        return _finish(failure_report(report, outcome.kind, outcome.message, exercise), started)
    try:
        analysis = parent_analysis(exercise, Path(path)) if _has_static_checks(exercise) else None
    except PlcError as exc:
        return _finish(failure_report(report, load_error_kind(exc), str(exc), exercise), started)
    try:
        report.warnings += list(outcome.runs[0].warnings) if outcome.runs else []
        evaluate(exercise, outcome.runs, analysis, report)
        export(exercise, outcome.runs, report, rrd_dir=rrd_dir, plots_dir=plots_dir, traces_dir=traces_dir)
    except Exception as exc:  # noqa: BLE001 - our own bug: reported as the grader's, not the student's
        report.checks, report.runs = [], []
        failure_report(report, "grader error", f"{type(exc).__name__}: {exc}", exercise)
    return _finish(report, started)


def _finish(report: Report, started: float) -> Report:
    report.elapsed_s = time.perf_counter() - started
    return report


def _has_static_checks(exercise: Exercise) -> bool:
    return any(isinstance(c.check, StaticCheck) for c in exercise.checks)


def parent_analysis(exercise: Exercise, path: Path) -> Any:
    """The program's static analysis, computed here from its text (never taken from the child).

    This loads the program (parse, subset check, declarations) and compiles it against the exercise's
    tag table without running any network; it relies on the program loader evaluating module-level
    declarations without running submission code. Static checks read the Python front end's analysis,
    or another front end's ``analysis(tags)`` (None without one)."""
    program = read_program(path)
    if not isinstance(program, Program):
        analyse = getattr(program, "analysis", None)  # another front end's own analysis (it runs nothing)
        return analyse(exercise.tag_table()) if analyse is not None else None
    table = program.declare_into(exercise.tag_table())
    return program.compile(table).analysis


EXPORT_DIRS = ("rrd_dir", "plots_dir", "traces_dir")
"""The options of :func:`grade` naming folders the grader writes files into."""


def per_student(folder: str | Path | None, submission: Path) -> Path | None:
    """A student's own folder below ``folder`` (named like the submission's file, without ``.py``)."""
    return None if folder is None else Path(folder) / (submission.stem or "submission")


@dataclass(frozen=True)
class ExerciseRef:
    """How a grading process elsewhere imports the exercise: its module and attribute, and the folder
    to put on ``sys.path`` first for an instructor's exercise file found by path."""

    module: str
    attribute: str
    root: str | None = None

    @classmethod
    def of(cls, exercise: Exercise) -> ExerciseRef:
        """Raises ConfigurationError for an exercise no module defines (one built in a test or notebook)."""
        from plcsim.grading.sandbox.importable import locate, package_root

        module, attribute = locate(exercise)
        top = package_root(sys.modules[module])
        return cls(module, attribute, str(top.parent) if top is not None else None)

    def resolve(self) -> Exercise:
        if self.root is not None and self.module not in sys.modules and self.root not in sys.path:
            sys.path.append(self.root)  # last, like exercises.load_path: it never shadows an installed module
        exercise = getattr(importlib.import_module(self.module), self.attribute)
        if not isinstance(exercise, Exercise):
            raise ConfigurationError(f"{self.module}.{self.attribute} is not an Exercise here")
        return exercise


@dataclass(frozen=True)
class GradingTask:
    """One submission of a batch, as an executor ships it to the process that grades it."""

    exercise: Exercise | ExerciseRef
    """The exercise itself (threads of this process) or how to import it (another process)."""
    path: str
    seed: int
    limits: Limits | None
    probes: Any
    """The batch's :class:`plcsim.grading.sandbox.probes.Probes`, or None to probe in the task."""
    options: dict[str, Any]
    version: str


def grade_task(task: GradingTask) -> Report:
    """Grade one submission of a batch, wherever an executor runs this: the submission in its own
    confined child, the checks here. Whatever this raises becomes a grader error in :func:`grade_batch`."""

    if task.version != version.__version__:
        raise ConfigurationError(
            f"this grading worker runs plcsim {version.__version__}, the grader {task.version}: "
            f"install the same plcsim on every worker"
        )
    exercise = task.exercise.resolve() if isinstance(task.exercise, ExerciseRef) else task.exercise
    return grade_sandboxed(exercise, task.path, seed=task.seed, limits=task.limits, probes=task.probes, **task.options)


def grade_batch(
    exercise: Exercise,
    paths: Iterable[str | Path],
    *,
    jobs: int = 1,
    executor: str | Executor = "local",
    seed: int = 1,
    limits: Limits | None = None,
    progress: Callable[[int, int, Report], None] | None = None,
    **options: Any,
) -> list[Report]:
    """Grade many submissions, each in its own confined child process, through ``executor``.

    ``executor`` is ``"local"`` (``jobs`` threads here), ``"dask"`` (a Dask cluster of ``jobs`` worker
    processes on this machine), an existing Dask scheduler's address (``"tcp://host:8786"``), see
    :mod:`plcsim.grading.executors`, or any ``concurrent.futures.Executor`` (left open). The reports come in
    the order of ``paths``, whatever order they finish in; a task that fails (its worker died, the
    cluster is gone) is a grader error of that submission alone. ``progress(done, total, report)`` is
    called as each finishes. The trusted probe runs once per scenario for the whole batch.

    Recordings, traces and diagrams (``rrd_dir``, ``traces_dir``, ``plots_dir``) go into one folder per
    student below the folder given (``out/alice/led-1-alice-presses.rrd``)."""
    from plcsim.grading.executors import open_executor
    from plcsim.grading.sandbox.probes import Probes

    paths = [Path(p) for p in paths]
    reports: list[Report | None] = [None] * len(paths)
    try:
        probes = Probes.of(exercise, chosen_scenarios(exercise, options.get("scenarios")), seed)
    except Exception:  # noqa: BLE001 - the exercise's mistake: each task probes again and reports it
        probes = None
    opened = open_executor(executor, jobs=jobs) if isinstance(executor, str) else contextlib.nullcontext(executor)
    with opened as pool:
        target = exercise if isinstance(pool, ThreadPoolExecutor) else ExerciseRef.of(exercise)
        futures: dict[Future[Report], int] = {}
        for k, path in enumerate(paths):
            mine = {key: per_student(value, path) if key in EXPORT_DIRS else value for key, value in options.items()}
            task = GradingTask(target, str(path), seed, limits, probes, mine, version.__version__)
            futures[pool.submit(grade_task, task)] = k
        for done, future in enumerate(as_completed(futures), start=1):
            k = futures[future]
            reports[k] = _task_report(future, exercise, paths[k], seed)
            if progress is not None:
                progress(done, len(paths), reports[k])
    return [r for r in reports if r is not None]


def _task_report(future: Future[Report], exercise: Exercise, path: Path, seed: int) -> Report:
    """The task's report, or, if the task itself failed, a grader error of this submission alone."""
    try:
        report = future.result()
    except Exception as exc:  # noqa: BLE001 - a dead worker, a lost cluster, our own bug: never the student's
        message = (
            f"the grading task failed ({type(exc).__name__}: {exc}); the submission was not graded "
            f"(a fault of the grader or its workers, not of the submission)"
        )
        blank = Report(exercise.number, exercise.title, str(path), seed=seed)
        return failure_report(blank, "grader error", message, exercise)
    return report
