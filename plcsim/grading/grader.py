"""Grade one submission: run it in every scenario of an exercise, evaluate the checks, report.

Grading has two halves that both paths share: :func:`run_scenarios` (:mod:`plcsim.grading.run`) runs
the program and returns raw results (traces, CPU state; no score), :func:`evaluate`
(:mod:`plcsim.grading.scoring`) runs the exercise's checks on them and builds the :class:`Report`.
:func:`grade` does both in this process (trusted code: tests, notebooks). :func:`grade_sandboxed` runs
the first half in a confined child process (:mod:`plcsim.grading.sandbox.parent`) and the second here,
on results validated by :mod:`plcsim.grading.run_result`: what the child sends can lose points, never
earn them. Exporters (rerun recordings, timing diagrams, ``.npz`` traces: :mod:`plcsim.grading.export`)
run here too, from the returned traces, so a grade never depends on which files were asked for. A
batch grades each submission with :func:`grade_sandboxed` (:mod:`plcsim.grading.batch`).
"""

from __future__ import annotations

import time
from collections.abc import Sequence
from dataclasses import replace
from pathlib import Path
from typing import Any

from plcsim.check import StaticCheck
from plcsim.controllers.loaded import SourceProgram
from plcsim.core.errors import PlcError
from plcsim.exercise.model import Exercise
from plcsim.frontends import read_program
from plcsim.frontends.python.program import Program
from plcsim.grading.export import export
from plcsim.grading.report import Report
from plcsim.grading.run import chosen_scenarios, load_error_kind, run_scenarios
from plcsim.grading.sandbox.limits import Budget, Limits
from plcsim.grading.scoring import evaluate, failure_report


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
        runs, analysis = run_scenarios(exercise, program, seed=seed, scenarios=scenarios, geometry=rrd_dir is not None)
    except PlcError as exc:
        failure_report(report, load_error_kind(exc), str(exc), exercise)
    else:
        report.warnings = list(runs[0].warnings) if runs else []
        evaluate(exercise, runs, analysis, report)
        export(exercise, runs, report, rrd_dir=rrd_dir, plots_dir=plots_dir, traces_dir=traces_dir, program=program)
    return _finish(report, started)


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
    """Grade an untrusted submission file: run it in a confined child (:mod:`plcsim.grading.sandbox.parent`),
    check here.

    ``child_entry`` (tests only) names another child module to start, to prove what the grader does
    with a hostile child's output. ``probes``: a batch's :class:`plcsim.grading.sandbox.probes.Probes`."""
    from plcsim.grading.sandbox.parent import DEFAULT_ENTRY, run_child

    limits = limits or Limits()
    if limits.budget is None and exercise.cpu_budget_s is not None:  # the exercise's own; a batch fits one
        limits = replace(limits, budget=Budget.of_exercise(exercise.cpu_budget_s))
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
        drawn = _python_program(Path(path)) if plots_dir is not None else None
        export(
            exercise, outcome.runs, report, rrd_dir=rrd_dir, plots_dir=plots_dir, traces_dir=traces_dir, program=drawn
        )
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


def _python_program(path: Path) -> Any:
    """The submission read as a Python program for its ladder picture (parsed and checked here, never run;
    None for another language or a file that does not read)."""
    if path.suffix != ".py":
        return None
    from plcsim.frontends.python.program import Program

    try:
        return Program.from_file(path)
    except PlcError:
        return None
