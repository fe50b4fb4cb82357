"""``plcsim run``: a program on an exercise's rig or a bare rig, with a summary, a grade of the run, and the
recording, timing diagram or trace asked for."""

from __future__ import annotations

import argparse
import time
from pathlib import Path
from typing import Any

from plcsim.apps.cli.exits import EXIT_FAILED
from plcsim.apps.cli.verdicts import print_verdicts, shipped_solution
from plcsim.core.errors import ConfigurationError, PlcError
from plcsim.core.registry import is_rig, rig, rig_names


def run_command(args: argparse.Namespace) -> int:
    """``plcsim run``: the run, its summary, the files asked for, and on an exercise the run's grade."""
    from rich.console import Console
    from rich.markup import escape
    from rich.progress import BarColumn, Progress, TextColumn, TimeRemainingColumn
    from rich.text import Text

    from plcsim.check import evaluate_all
    from plcsim.core.untrusted_text import for_terminal
    from plcsim.frontends import read_program
    from plcsim.grading.terminal import print_run_summary

    console = Console()
    exercise = None
    saved = _saved_scenario(args)
    if is_rig(args.target):
        sim = _rig_simulation(args, saved)
        scenario_name = saved.name if saved else None
    else:
        from plcsim.core.errors import did_you_mean
        from plcsim.exercise.catalog import get

        try:
            exercise = get(args.target)
        except ConfigurationError as exc:  # neither an exercise nor a rig: name the rigs too
            rigs = rig_names()
            raise ConfigurationError(
                f"{exc}; the rigs are {', '.join(rigs)}{did_you_mean(args.target.upper(), rigs)}"
            ) from None
        if first := _first_program(args):
            program = first
        elif args.program:
            program = read_program(args.program)
        elif args.reference or args.solution:
            program = shipped_solution(exercise, args.solution).program()
        else:
            raise PlcError(
                f"which program? plcsim run {args.target} --program FILE.py runs yours; "
                f"--reference (or --solution NAME) runs a shipped one"
            )
        if saved is not None:
            scenario = saved
        else:
            scenario = exercise.scenario(args.scenario) if args.scenario else exercise.scenarios[0]
        scenario_name = scenario.name
        options = {"cycle": args.cycle} if args.cycle else {}
        sim = exercise.simulation(program, scenario, seed=args.seed, pacing=_pacing(args), **options)
    duration = int(args.seconds * 1e9) if args.seconds else (sim.scenario.duration_ns if sim.scenario else int(10e9))
    console.print(
        f"running {args.target}"
        + (f", scenario {scenario_name!r}" if scenario_name else "")
        + f" for {duration / 1e9:g} s simulated"
        + (f" at {args.realtime:g}× real time" if args.realtime else "")
    )
    wall0 = time.perf_counter()
    with Progress(
        TextColumn("[progress.description]{task.description}"),
        BarColumn(),
        TextColumn("{task.percentage:>3.0f}%"),
        TimeRemainingColumn(),
        console=console,
        transient=True,
        disable=duration < 20e9 and not args.realtime,
    ) as progress:
        task = progress.add_task("simulating", total=duration)
        error = None
        try:
            sim.run(duration, progress=lambda done, total: progress.update(task, completed=done))
        except PlcError as exc:
            error = exc
    wall = time.perf_counter() - wall0
    print_run_summary(sim, wall, console)
    if saved is not None:  # the live page shows the same digest for the same session
        console.print(f"seed {args.seed}, trace digest {sim.trace.digest()[:16]}")
    if error is not None:
        console.print(Text.assemble(("the run stopped:", "bold red"), f" {for_terminal(str(error), newlines=True)}"))
    if args.rrd:
        path = Path(args.rrd)
        path.parent.mkdir(parents=True, exist_ok=True)
        sim.trace.to_rrd(path)
        console.print(f"recording: {path}  (open it with: rerun {path})")
        if args.spawn_viewer:
            _spawn_viewer(path, console)
    if args.plot:
        from plcsim.trace.plot import save_timing_diagram

        path = Path(args.plot)
        path.parent.mkdir(parents=True, exist_ok=True)
        signals = args.signals.split(",") if args.signals else None
        save_timing_diagram(
            sim.trace, path, signals, title=f"{args.target}" + (f" — {scenario_name}" if scenario_name else "")
        )
        console.print(f"timing diagram: {path}")
    if args.trace:
        path = Path(args.trace)
        path.parent.mkdir(parents=True, exist_ok=True)
        sim.trace.save(path)
        console.print(f"trace: {path}")
    if exercise is None:
        return 0
    graded = [gc for gc in exercise.checks_for(scenario_name)]
    analysis = sim.cpu.compiled.analysis if sim.cpu.compiled else None
    results = evaluate_all([g.check for g in graded], sim.trace, analysis)
    passed = sum(v.passed for _, v in results)
    points = sum(c.weight for c, v in results if v.passed)
    total = sum(c.weight for c, _ in results)
    console.print(f"[bold]grade of this run[/] (scenario {scenario_name!r}, seed {args.seed}):")
    print_verdicts(results, console)
    console.print(
        f"[bold]{points:g} / {total:g}[/] points, {passed}/{len(results)} checks passed  "
        f"(grade every scenario with: plcsim grade {escape(_as_typed(args.target))} FILE.py)"
    )
    return 0 if passed == len(results) else EXIT_FAILED


def _as_typed(name: str) -> str:
    """An exercise as the user named it, quoted for a shell: the form a hint repeats (a file-loaded exercise's
    number is not found by number)."""
    import shlex

    return shlex.quote(name)


def _rig_simulation(args: argparse.Namespace, scenario: Any = None) -> Any:
    from plcsim.apps.live.build import rig_simulation
    from plcsim.apps.live.session import NO_PROGRAM
    from plcsim.frontends import read_program
    from plcsim.frontends.python.program import Program

    program = _first_program(args) or (
        read_program(args.program) if args.program else Program(NO_PROGRAM, "(no program)")
    )
    return rig_simulation(rig(args.target)(), program, scenario, seed=args.seed, cycle=args.cycle, pacing=_pacing(args))


def _saved_scenario(args: argparse.Namespace) -> Any:
    """``--scenario FILE.toml|.py``: a saved live session (its seed unless --seed says otherwise); else None."""
    if not (args.scenario and args.scenario.endswith((".toml", ".py"))):
        args.seed = 1 if args.seed is None else args.seed
        return None
    from plcsim.apps.live.build import Target
    from plcsim.apps.live.recording import load_scenario_file
    from plcsim.core.literals import format_ns

    base = None if is_rig(args.target) else _exercise_scenario(args.target)
    target = Target.find(args.target)
    scenario, seed, args.first_program = load_scenario_file(args.scenario, base=base, rig_verbs=target.verbs())
    limit = target.replay_limit_ns()
    if args.seconds is None and scenario.duration_ns > limit:  # a file must not make the run go on without bound
        raise PlcError(
            f"{args.scenario}: the scenario lasts {format_ns(scenario.duration_ns)}; a saved scenario on "
            f"{target.name} may last {format_ns(limit)} (an hour, or the exercise's longest scenario); "
            f"run it for N seconds with --seconds N"
        )
    args.seed = args.seed if args.seed is not None else (seed if seed is not None else 1)
    return scenario


def _first_program(args: argparse.Namespace) -> Any:
    """The program a saved live session started with, where it downloaded another (the file may have been
    edited since; the replay starts from the text as it was, and says so if the file now differs)."""
    text = getattr(args, "first_program", None)
    if text is None:
        return None
    from plcsim.frontends.python.program import Program

    name = args.program or "<the session's first program>"
    if args.program and Path(args.program).is_file() and Path(args.program).read_text(encoding="utf-8") != text:
        print(
            f"note: {args.scenario} holds the program the session started with; {args.program} has changed "
            "since, so the replay starts from the text as it was (the downloads follow, as recorded)"
        )
    return Program(text, name)


def _exercise_scenario(target: str) -> Any:
    from plcsim.exercise.catalog import get

    return get(target).scenario


def _pacing(args: argparse.Namespace) -> Any:
    """``--realtime F``: the run keeps pace with the wall clock × F; otherwise as fast as it goes."""
    from plcsim.sim.simulation import Realtime

    return Realtime(args.realtime) if args.realtime else None


def _spawn_viewer(path: Path, console: Any) -> None:
    import shutil
    import subprocess

    exe = shutil.which("rerun")
    if exe is None:
        console.print("[yellow]the rerun viewer is not on PATH; open the file with `rerun` yourself[/]")
        return
    subprocess.Popen([exe, str(path)])
