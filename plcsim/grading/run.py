"""Run a program in the scenarios of an exercise: the raw results (traces, CPU state; no score).

This is the half of grading that runs submission code, so it is the bottom of the grading package:
the grader calls it in this process (:mod:`plcsim.grading.grader`) and the sandbox's confined child
calls it there (:mod:`plcsim.grading.sandbox.child`), and it calls neither of them. The checks are
evaluated elsewhere, on what it returns (:mod:`plcsim.grading.scoring`).
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

from plcsim.core.errors import ConfigurationError, PlcError, SubsetError
from plcsim.exercise.model import Exercise
from plcsim.frontends.python.program import Program
from plcsim.grading.run_result import RunResult


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
    exercise: Exercise,
    program: Program,
    *,
    seed: int,
    scenarios: Sequence[str] | None = None,
    geometry: bool = True,
) -> tuple[list[RunResult], Any]:
    """Run ``program`` in each chosen scenario: the raw results and the program's static analysis.
    ``geometry`` False samples no drawing frames (no check reads them; only a recording needs them).

    Raises PlcError if the program cannot be loaded on the exercise's CPU."""
    results, analysis = [], None
    for scenario in chosen_scenarios(exercise, scenarios):
        sim = exercise.simulation(program, scenario, seed=seed, geometry=geometry)
        if analysis is None and sim.cpu.compiled is not None:
            analysis = sim.cpu.compiled.analysis
        plant_error = None
        try:
            sim.run()
        except ConfigurationError:  # the exercise's mistake (ExerciseError): the grader's, not a plant failure
            raise
        except PlcError as exc:  # a plant failure: the run ends early (see plcsim.grading.scoring.evaluate)
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
