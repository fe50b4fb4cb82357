"""Grading: run a submission, evaluate the checks, report; batches and the sandbox."""

from plcsim.grading.grader import (
    CheckResult,
    Limits,
    Report,
    ScenarioRun,
    evaluate,
    grade,
    grade_batch,
    grade_sandboxed,
    load_error_kind,
    max_score,
    run_scenarios,
    write_gradebook,
    write_junit,
)

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
