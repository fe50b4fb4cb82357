"""Group ``digests``: has a change altered what any shipped solution does? (a check, not a timing)

Figure ``solutions_trace_digest``: every shipped solution of every exercise, run in every scenario on the
seeds 0 and 7 (or those of ``--seeds``: ``--seeds 1 2 3`` are the ones the test suite uses), gives one
line ``exercise solution seed scenario trace-digest scans mode error plant-error``;
the value is the sha256 of all the lines. A refactoring that must not change behaviour (a move, a split)
prints the same value before and after, bit for bit; ``--quick`` runs the first two exercises on seed 0.
``broken_exercises`` names the exercise modules that did not load (their solutions are not in the digest): a
run from a git worktree whose ``plants`` resolves to another checkout's shows it there, not as a new digest.
"""

from __future__ import annotations

import hashlib
from collections.abc import Iterator

from benchmarks.harness import Figure, Settings, figure, progress

SEEDS = (0, 7)


def lines(quick: bool, seeds: tuple[int, ...] = SEEDS) -> Iterator[str]:
    """One line per (solution, seed, scenario) run, in the catalogue's order."""
    import exercises
    from plcsim.core.errors import PlcError
    from plcsim.grading import run_scenarios

    chosen = exercises.all_exercises()[:2] if quick else exercises.all_exercises()
    for ex in chosen:
        for solution in ex.solutions:
            for seed in seeds[:1] if quick else seeds:
                try:
                    runs, _ = run_scenarios(ex, solution.program(), seed=seed)
                except PlcError as exc:
                    yield f"{ex.number} {solution.name} {seed} LOAD-ERROR {type(exc).__name__} {exc}"
                    continue
                for r in runs:
                    yield (
                        f"{ex.number} {solution.name} {seed} {r.scenario} {r.trace.digest()} {r.scans} "
                        f"{r.cpu_mode} {r.cpu_error} {r.plant_error}"
                    )


def run(settings: Settings) -> Iterator[Figure]:
    progress("digests: every shipped solution in every scenario")
    import exercises

    seeds = settings.seeds or SEEDS
    every = list(lines(settings.quick, seeds))
    digest = hashlib.sha256("\n".join(every).encode()).hexdigest()
    broken = [f"{b.file}:{b.line}: {b.error}" for b in exercises.broken_exercises()]
    yield figure(
        "solutions_trace_digest",
        digest,
        "sha256",
        runs=len(every),
        seeds=list(seeds[:1] if settings.quick else seeds),
        broken_exercises=broken[:3] + ([f"... {len(broken) - 3} more"] if len(broken) > 3 else []),
    )
