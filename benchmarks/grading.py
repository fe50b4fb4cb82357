"""Grading figure: every shipped solution (references, alternatives and wrong ones) of every exercise,
each in its own sandboxed child process, two at a time, as ``plcsim grade ... --jobs 2`` does.
Budget: < 60 s on 2 cores."""

from __future__ import annotations

import time
from collections.abc import Iterator
from concurrent.futures import ThreadPoolExecutor
from typing import Any

from benchmarks.harness import Settings, figure, progress


def run(settings: Settings) -> Iterator[dict[str, Any]]:
    from exercises import all_exercises
    from plcsim.grading import grade_sandboxed

    jobs = [(ex, sol) for ex in all_exercises() for sol in ex.solutions]
    if settings.quick:
        jobs = jobs[:2]
    per_exercise: dict[str, float] = {}
    unexpected: list[str] = []

    def one(job: tuple[Any, Any]) -> tuple[Any, Any, Any]:
        ex, sol = job
        return ex, sol, grade_sandboxed(ex, sol.path, seed=1, scenarios=sol.scenarios)

    t0 = time.perf_counter()
    with ThreadPoolExecutor(max_workers=2) as pool:
        for ex, sol, report in pool.map(one, jobs):
            per_exercise[ex.number] = per_exercise.get(ex.number, 0.0) + report.elapsed_s
            ok = report.passed if sol.kind in ("reference", "alternative") else not report.passed
            if not ok or report.error:
                unexpected.append(f"{ex.number}/{sol.name}")
    wall = time.perf_counter() - t0
    progress(f"graded {len(jobs)} solutions in {wall:.1f} s")
    slowest = sorted(per_exercise.items(), key=lambda kv: -kv[1])[:5]
    yield figure(
        "grade_all_solutions_s",
        round(wall, 2),
        "s",
        budget="< 60",
        jobs=2,
        solutions=len(jobs),
        exercises=len(per_exercise),
        slowest={k: round(v, 2) for k, v in slowest},
        unexpected=unexpected,
    )
