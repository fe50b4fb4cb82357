"""The instructors' commands: check an exercise's own programs, mutation-test its checks."""

from __future__ import annotations

import argparse
from pathlib import Path
from typing import Any

from plcsim.apps.cli.exits import EXIT_FAILED
from plcsim.core.errors import PlcError


def check_exercise_command(args: argparse.Namespace) -> int:
    """``plcsim check-exercise``: every program the exercises ship, graded on seeds 1..N against what it claims."""
    from rich.console import Console
    from rich.text import Text

    from plcsim.apps.check_exercise import check_exercise, print_exercise_check
    from plcsim.exercise.catalog import get, is_path, load_path

    if args.seeds < 1:
        raise PlcError("--seeds must be at least 1")
    console = Console()
    exercises, broken = [], []
    for name in args.exercise:
        if is_path(name):
            loaded, unloaded = load_path(name)
            exercises += loaded
            broken += unloaded
        else:
            exercises.append(get(name))
    for bad in broken:
        console.print(Text.assemble(("not loaded: ", "bold red"), str(bad)))
    seeds = range(1, args.seeds + 1)
    ok = not broken
    for exercise in exercises:
        results = check_exercise(exercise, seeds)
        print_exercise_check(exercise, results, console)
        ok = ok and all(r.ok for r in results)
    return 0 if ok else EXIT_FAILED


def mutate_command(args: argparse.Namespace) -> int:
    """``plcsim mutate``: the reference's mutants graded; exit 1 where a survivor shows a check misleads."""
    from rich.console import Console
    from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn

    from plcsim.exercise.catalog import get
    from plcsim.mutate.engine import mutate_exercise, print_mutation_report

    if args.seeds < 1 or args.jobs < 1:
        raise PlcError("--seeds and --jobs must be at least 1")
    console = Console()
    columns = (TextColumn("grading mutants"), BarColumn(), MofNCompleteColumn())
    with Progress(*columns, console=console, transient=True, auto_refresh=False) as bar:  # no thread: workers fork
        task = bar.add_task("", total=None)

        def step(done: int, total: int, _: Any) -> None:
            bar.update(task, completed=done, total=total)
            bar.refresh()

        report = mutate_exercise(get(args.exercise), seeds=args.seeds, jobs=args.jobs, progress=step)
    print_mutation_report(report, console)
    if args.json:
        Path(args.json).parent.mkdir(parents=True, exist_ok=True)
        report.to_json(args.json)
        console.print(f"JSON report: {args.json}", highlight=False)
    return EXIT_FAILED if report.misleading else 0
