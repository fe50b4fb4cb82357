"""Grading figures.

``grade_all_solutions_s``: every shipped solution (references, alternatives and wrong ones) of every
exercise, each in its own sandboxed child process, two at a time, as ``plcsim grade ... --jobs 2``
does. Budget: < 60 s on 2 cores.

``grading_rate_*``: submissions graded per second by ``grade_batch`` (one class folder per exercise:
the shipped solutions of a few small exercises) with 1 and 2 local threads (``--jobs 1``, ``--jobs
2``) and on a Dask ``LocalCluster`` of two worker processes (``--executor dask --jobs 2``). The class
is graded twice on each executor: the figure is the second pass (steady state); the first pass
(``first_pass_s``: a worker's first tasks import the exercises) and the cluster's start-up
(``startup_s``) are given apart, and ``with_startup`` is the rate of one pass with both.
"""

from __future__ import annotations

import time
from collections.abc import Iterator
from concurrent.futures import ThreadPoolExecutor
from typing import Any

from benchmarks.harness import Settings, figure, progress

CLASS = ("4.3.1", "4.3.2", "4.3.4")
"""The exercises whose shipped solutions make the class of the rate figures (10 submissions)."""


def run(settings: Settings) -> Iterator[dict[str, Any]]:
    yield _all_solutions(settings)
    yield from _rates(settings)


def _all_solutions(settings: Settings) -> dict[str, Any]:
    from exercises import all_exercises
    from plcsim.grading.grader import grade_sandboxed

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
    return figure(
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


def _rates(settings: Settings) -> Iterator[dict[str, Any]]:
    from exercises import get
    from plcsim.grading.executors import open_executor

    classes = [(ex, [s.path for s in ex.solutions]) for ex in map(get, CLASS[:1] if settings.quick else CLASS)]
    if settings.quick:
        classes = [(ex, paths[:2]) for ex, paths in classes]
    count = sum(len(paths) for _, paths in classes)
    for name, spec, jobs in (("jobs1", "local", 1), ("jobs2", "local", 2), ("dask_local2", "dask", 2)):
        t0 = time.perf_counter()
        with open_executor(spec, jobs=jobs) as pool:
            startup = time.perf_counter() - t0
            first, failures = _grade_class(classes, pool)
            seconds, more = _grade_class(classes, pool)
        context = {"executor": spec, "workers": jobs, "submissions": count, "seconds": round(seconds, 2)}
        context |= {"first_pass_s": round(first, 2), "startup_s": round(startup, 2)}
        context |= {"with_startup": round(count / (startup + first), 2)}
        failures += more
        progress(f"{name}: {count} submissions in {seconds:.1f} s (first pass {first:.1f} s, start-up {startup:.1f} s)")
        yield figure(f"grading_rate_{name}", round(count / seconds, 2), "submissions/s", **context, unexpected=failures)


def _grade_class(classes: list[tuple[Any, list[Any]]], pool: Any) -> tuple[float, list[str]]:
    """Grade each exercise's folder through ``pool``: the seconds taken and the grades that went wrong."""
    from plcsim.grading.batch import grade_batch

    unexpected = []
    t0 = time.perf_counter()
    for ex, paths in classes:
        for report in grade_batch(ex, paths, executor=pool):
            kind = next(s.kind for s in ex.solutions if str(s.path) == report.submission)
            if report.error or report.passed != (kind in ("reference", "alternative")):
                unexpected.append(f"{ex.number}/{report.student}")
    return time.perf_counter() - t0, unexpected
