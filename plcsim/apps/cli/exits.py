"""The exit codes of the ``plcsim`` command, and the code a list of grade reports ends with."""

from __future__ import annotations

from typing import Any

EXIT_FAILED = 1
"""A submission failed (or did not run)."""
EXIT_USAGE = 2
"""A usage error: a wrong option, an unknown exercise, a file that does not load."""
EXIT_GRADER = 3
"""A grade is void because of the grader or the exercise (a check that raised), not the submission."""


def exit_code(reports: list[Any]) -> int:
    """0 if every submission passed, EXIT_GRADER if a grade is void through the grader's fault, else 1."""
    if any(r.grader_failed for r in reports):
        return EXIT_GRADER
    return 0 if all(r.passed for r in reports) else EXIT_FAILED
