"""The CPU budget of an exercise's submissions, fitted to the task: measured once per batch.

A submission is bounded by the absolute limits (60 s of CPU, 120 s of wall time); an exercise whose
reference grades in a second needs far less, and ten slow files would otherwise stall a batch for
minutes. :func:`fitted_limits` runs the exercise's reference once here, in the scenarios and seed of the
batch, and measures the CPU time of this thread while it runs (not wall time, not the other threads of
the grader: a loaded machine or a progress bar does not move it). The budget is
:data:`~plcsim.grading.sandbox.limits.MULTIPLE` times that, never below
:data:`~plcsim.grading.sandbox.limits.FLOOR_S` (which also covers a child's start-up, which the reference
run here does not pay); an exercise may set its own (``cpu_budget_s``). If the reference cannot be
measured, there is no budget: the grader's trouble is never charged to a student.
"""

from __future__ import annotations

import time
from collections.abc import Sequence
from dataclasses import replace

from plcsim.exercise.model import Exercise
from plcsim.frontends import read_program
from plcsim.grading.run import run_scenarios
from plcsim.grading.sandbox.limits import Budget, Limits


def fitted_limits(exercise: Exercise, limits: Limits, *, seed: int, scenarios: Sequence[str] | None = None) -> Limits:
    """``limits`` with the exercise's CPU budget: its own ``cpu_budget_s``, or fitted to its reference's
    measured CPU time; ``limits`` unchanged if the reference does not run cleanly here."""
    if exercise.cpu_budget_s is not None:
        return replace(limits, budget=Budget.of_exercise(exercise.cpu_budget_s))
    cost = reference_cpu_s(exercise, seed, scenarios)
    return limits if cost is None else replace(limits, budget=Budget.fitted(cost))


def reference_cpu_s(exercise: Exercise, seed: int, scenarios: Sequence[str] | None = None) -> float | None:
    """The CPU seconds this thread spends running the exercise's reference (None if it has none or it
    does not run to the end of its scenarios). 0.0 is a measurement: Windows counts thread time in ticks of
    about 16 ms, and a reference shorter than one measures 0.0 s there."""
    try:
        program = read_program(exercise.reference.path)
        started = time.thread_time()
        runs, _ = run_scenarios(exercise, program, seed=seed, scenarios=scenarios)
        cost = time.thread_time() - started
    except Exception:  # noqa: BLE001 - no reference, or it cannot run: no budget, never the student's cost
        return None
    return cost if runs and not any(run.cpu_error or run.plant_error for run in runs) else None
