"""Mutation figures: the score of every exercise's checks against mutants of its reference
(``plcsim mutate``), and what the sweep costs.

One figure per exercise (``mutation_score_<number>``: killed / mutants that change behaviour, with
the counts, the seconds and the surviving mutants), then the sweep's totals. Seeds 1..3, two
mutants at a time (the machine's two cores); ``--quick`` grades only 4.3.1 on one seed.
"""

from __future__ import annotations

import time
from collections.abc import Iterator
from typing import Any

from benchmarks.harness import Settings, figure, progress

SEEDS = 3
JOBS = 2


def run(settings: Settings) -> Iterator[dict[str, Any]]:
    from exercises import all_exercises, get
    from plcsim.mutate import EQUIVALENT, KILLED, STILLBORN, SURVIVED, mutate_exercise

    chosen = [get("4.3.1")] if settings.quick else list(all_exercises())
    seeds = 1 if settings.quick else SEEDS
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
            equivalent=report.count(EQUIVALENT),
            stillborn=report.count(STILLBORN),
            seconds=round(report.elapsed_s, 2),
            seeds=seeds,
            survivors=[f"{o.mutant} ({o.detail})" for o in report.of(SURVIVED)],
            reference_failures=report.reference_failures,
        )
    wall = time.perf_counter() - t0
    yield figure(
        "mutation_sweep_s", round(wall, 1), "s", exercises=len(chosen), mutants=mutants, seeds=seeds, jobs=JOBS
    )
    yield figure(
        "mutation_score_min",
        round(min(scores), 3) if scores else None,
        "killed / behaviour-changing mutants",
        exercises=len(scores),
    )
