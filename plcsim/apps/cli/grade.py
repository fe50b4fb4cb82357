"""``plcsim grade``: a submission or a folder of them, sandboxed, with the reports an LMS reads."""

from __future__ import annotations

import argparse
from pathlib import Path

from plcsim.apps.cli.exits import exit_code
from plcsim.apps.cli.verdicts import shipped_solution
from plcsim.core.errors import PlcError


def grade_command(args: argparse.Namespace) -> int:
    """``plcsim grade``: one submission (its report) or a folder of them (a line each, and the batch's files)."""
    from rich.console import Console
    from rich.progress import BarColumn, MofNCompleteColumn, Progress, TextColumn

    from plcsim.exercise.catalog import get
    from plcsim.grading.batch import grade_batch
    from plcsim.grading.grader import grade, grade_sandboxed
    from plcsim.grading.report import file_stems, write_gradebook, write_gradescope, write_junit
    from plcsim.grading.sandbox.limits import Limits
    from plcsim.grading.terminal import print_batch_line, print_report

    console = Console()
    limits = Limits(cpu_seconds=args.cpu_seconds, memory_mb=args.memory_mb)  # refused here if not positive
    exercise = get(args.exercise)
    options = {"rrd_dir": args.rrd, "plots_dir": args.plots}
    visibility = args.gradescope_visibility
    if args.reference or args.solution:
        target = shipped_solution(exercise, args.solution).path
    elif args.submission:
        target = Path(args.submission)
    else:
        raise PlcError("give a submission file or folder, or --reference / --solution NAME")
    if Path(target).is_dir():
        from plcsim.frontends import suffixes

        files = sorted(p for p in Path(target).iterdir() if p.is_file() and p.suffix.lower() in suffixes())
        if not files:
            raise PlcError(f"no program files ({', '.join(sorted(suffixes()))}) in {target}")
        with Progress(
            TextColumn("grading"), BarColumn(), MofNCompleteColumn(), TextColumn("{task.description}"), console=console
        ) as progress:
            task = progress.add_task("", total=len(files))
            reports = grade_batch(
                exercise,
                files,
                jobs=args.jobs,
                executor=args.executor,
                seed=args.seed,
                limits=limits,
                progress=lambda done, total, r: progress.update(task, completed=done),
                budget=not args.no_budget,
                **options,
            )
        for r in reports:
            print_batch_line(r, console)
        stems = file_stems([r.submission for r in reports])  # alice.py and alice.il: alice.py.json, alice.il.json
        if args.gradebook:
            Path(args.gradebook).parent.mkdir(parents=True, exist_ok=True)
            console.print(f"gradebook: {write_gradebook(reports, args.gradebook)}", markup=False)
        if args.json:
            out = Path(args.json)
            out.mkdir(parents=True, exist_ok=True)
            for r, stem in zip(reports, stems, strict=True):
                r.to_json(out / f"{stem}.json")
        if args.junit:
            Path(args.junit).parent.mkdir(parents=True, exist_ok=True)
            write_junit(reports, args.junit, name=f"plcsim {exercise.number}")
            console.print(f"JUnit report: {args.junit}", markup=False)
        if args.gradescope:
            for r, stem in zip(reports, stems, strict=True):
                write_gradescope(r, Path(args.gradescope) / stem / "results.json", visibility=visibility)
            console.print(f"Gradescope results: {args.gradescope}/<student>/results.json", markup=False)
        return exit_code(reports)
    if args.no_sandbox:
        report = grade(exercise, target, seed=args.seed, **options)
    else:
        report = grade_sandboxed(exercise, target, seed=args.seed, limits=limits, **options)
    print_report(report, console, verbose=args.verbose, quiet=args.quiet)
    if args.json:
        Path(args.json).parent.mkdir(parents=True, exist_ok=True)
        report.to_json(args.json)
        console.print(f"JSON report: {args.json}", markup=False)
    if args.junit:
        Path(args.junit).parent.mkdir(parents=True, exist_ok=True)
        report.to_junit(args.junit)
        console.print(f"JUnit report: {args.junit}", markup=False)
    if args.gradescope:
        written = write_gradescope(report, args.gradescope, visibility=visibility)
        console.print(f"Gradescope results: {written}", markup=False)
    return exit_code([report])
