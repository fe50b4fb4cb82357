"""Evaluate an exercise's checks on the raw results of a run and build the :class:`Report`.

This is the half of grading that runs no submission code: it reads the traces that
:mod:`plcsim.grading.run` produced, in this process or in the sandbox's child (validated by
:mod:`plcsim.grading.run_result`), so what a child sends can lose points, never earn them. A check
that raises is the exercise's or the grader's fault (:class:`GraderError`), never the student's.
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path
from typing import Any

from plcsim.check import StaticCheck
from plcsim.check.base import Context
from plcsim.check.exercised import Activity, scenario_writes, unprovoked
from plcsim.core.literals import format_ns
from plcsim.exercise.model import Exercise
from plcsim.grading.report import NOT_EXERCISED, CheckResult, Report, ScenarioRun
from plcsim.grading.run_result import RunResult


class GraderError(Exception):
    """A check of the exercise failed to evaluate: the instructor's or the grader's bug."""


def evaluate(exercise: Exercise, runs: Sequence[RunResult], analysis: Any, report: Report) -> Report:
    """Evaluate the exercise's checks on the runs (static checks once, on ``analysis``) into ``report``.

    A run that ended before its scenario did fails its run-time checks: a partial trace proves nothing.
    A check that holds only because the program never drove what it guards is *not exercised*
    (:mod:`plcsim.check.exercised`): 0 points. A check that raises is a grader error (its own outcome),
    never a point lost by the student.

    A program the exercise ships as correct (:func:`ships_as_correct`, the report's file) that fails a check because
    the run gave it nothing to check shows the exercise's mistake: the message says how to apply the check only in
    the scenarios that can show it.
    """
    correct = ships_as_correct(exercise, report.submission)
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
                result, nothing_to_check = _check(gc, ctx, run, static, cut_short, durations[run.scenario])
                if correct and nothing_to_check:
                    result.message += _restrict_hint(gc, list(durations), run.scenario)
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


def _check(
    gc: Any, ctx: Context, run: RunResult, static: bool, cut_short: bool, duration_ns: int
) -> tuple[CheckResult, bool]:
    """The check's result in this run, and whether it failed for want of anything to check."""
    weight = gc.check.weight
    if cut_short and not static:
        why = run.plant_error or run.cpu_error or "no reason given"
        message = f"the run ended at {format_ns(run.simulated_ns)} of {format_ns(duration_ns)} ({why}); not checked"
        return CheckResult(run.scenario, gc.name, False, message, 0.0, weight), False
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
    result = CheckResult(
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
    return result, not verdict.passed and verdict.nothing_to_check and not static


def ships_as_correct(exercise: Exercise, program: str) -> bool:
    """Whether the file ``program`` is the exercise's reference or a correct alternative it ships."""
    try:
        path = Path(program).resolve()
    except (TypeError, ValueError, OSError):
        return False
    return any(s.kind != "wrong" and Path(s.path).resolve() == path for s in exercise.solutions)


def _restrict_hint(gc: Any, scenarios: list[str], scenario: str) -> str:
    """How to apply a check only where it can apply: the scenarios it applies to now, but ``scenario``."""
    others = [s for s in scenarios if s != scenario and (gc.scenarios is None or s in gc.scenarios)]
    return (
        f"; a correct program gave this check nothing to check in scenario {scenario!r}: if that scenario cannot "
        f"show it, apply the check only where it can: only(check, {', '.join(map(repr, others))}) in the exercise"
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
