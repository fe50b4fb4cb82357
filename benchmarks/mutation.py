"""Mutation figures: the score of every exercise's checks against mutants of its reference
(``plcsim mutate``), and what the sweep costs.

One figure per exercise (``mutation_score_<number>``: killed / mutants that change behaviour, with
the counts, the seconds, the surviving mutants and the explained ones with the exercise's reason),
then the sweep's totals with the machine's load average before and after (the seconds of a shared
machine mean little without it). Every exercise, whatever its reference's language (S7 Python, Tecomat
instruction list, PLC836 mechanisms). Seeds 1..3, two mutants at a time (the machine's two cores);
``--quick`` grades only 4.3.1 on one seed.
"""

from __future__ import annotations

import os
import time
from collections.abc import Iterator
from typing import Any

from benchmarks.harness import Settings, figure, progress

SEEDS = 3
JOBS = 2


def run(settings: Settings) -> Iterator[dict[str, Any]]:
    from exercises import all_exercises, get
    from plcsim.mutate.engine import EQUIVALENT, EXPLAINED, KILLED, STILLBORN, SURVIVED, mutate_exercise

    chosen = [get("4.3.1")] if settings.quick else list(all_exercises())
    seeds = 1 if settings.quick else SEEDS
    load_before = _load()
    t0 = time.perf_counter()
    mutants = 0
    scores = []
    for exercise in chosen:
        report = mutate_exercise(exercise, seeds=seeds, jobs=JOBS)
        mutants += len(report.outcomes)
        if report.score is not None:
            scores.append(report.score)
        progress(f"{exercise.number}: {len(report.outcomes)} mutants in {report.elapsed_s:.1f} s")
        yield figure(
            f"mutation_score_{exercise.number}",
            None if report.score is None else round(report.score, 3),
            "killed / behaviour-changing mutants",
            target=">= 0.9",
            mutants=len(report.outcomes),
            killed=report.count(KILLED),
            survived=report.count(SURVIVED),
            explained=report.count(EXPLAINED),
            equivalent=report.count(EQUIVALENT),
            stillborn=report.count(STILLBORN),
            seconds=round(report.elapsed_s, 2),
            seeds=seeds,
            survivors=[f"{o.mutant} ({o.detail})" for o in report.of(SURVIVED)],
            explained_mutants=[f"{o.mutant}: {o.reason}" for o in report.of(EXPLAINED)],
            misleading_declarations=report.misleading,
            reference_failures=report.reference_failures,
        )
    wall = time.perf_counter() - t0
    yield figure(
        "mutation_sweep_s",
        round(wall, 1),
        "s",
        exercises=len(chosen),
        mutants=mutants,
        seeds=seeds,
        jobs=JOBS,
        load_before=load_before,
        load_after=_load(),
    )
    yield figure(
        "mutation_score_min",
        round(min(scores), 3) if scores else None,
        "killed / behaviour-changing mutants",
        exercises=len(scores),
    )


def _load() -> float | None:
    """The 1-minute load average (None where the platform has none, as on Windows)."""
    return round(os.getloadavg()[0], 2) if hasattr(os, "getloadavg") else None
