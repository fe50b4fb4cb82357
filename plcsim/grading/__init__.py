"""Grading: run a submission, evaluate the checks, report; batches and the sandbox."""

from plcsim.grading.batch import grade_batch
from plcsim.grading.grader import grade, grade_sandboxed
from plcsim.grading.report import CheckResult, Report, ScenarioRun, write_gradebook, write_junit
from plcsim.grading.run import load_error_kind, run_scenarios
from plcsim.grading.sandbox.limits import Limits
from plcsim.grading.scoring import evaluate, max_score

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
