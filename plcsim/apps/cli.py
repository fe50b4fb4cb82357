"""The ``plcsim`` command: list and show exercises, run a program on a rig, grade submissions::

    plcsim list
    plcsim show 4.3.7                 # the student's view; --solutions for instructors
    plcsim run 4.3.7 --reference --rrd out/run.rrd
    plcsim run CONV1 --program my_conveyor.py --seconds 20 --plot out/conveyor.png
    plcsim grade 4.3.7 my_alarm.py --json out/report.json --junit out/report.xml
    plcsim grade 4.3.7 submissions/ --jobs 2 --gradebook out/grades.csv --junit out/grades.xml
    plcsim mutate 4.3.7 --seeds 3 --jobs 2 --json out/mutants.json
    plcsim check-exercise my_course/runon.py --seeds 3
    plcsim draw SORT -o out/sort.png

Exit codes: 0 every check passed, 1 a submission failed (or did not run), 2 a usage error,
3 a grade is void because of the grader or the exercise (a check that raised).
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path
from typing import Any

from plcsim.core import version
from plcsim.core.errors import ConfigurationError, PlcError
from plcsim.core.registry import is_rig, rig, rig_names

EXIT_FAILED = 1
EXIT_USAGE = 2
EXIT_GRADER = 3
"""A grade is void because of the grader or the exercise (a check that raised), not the submission."""


def _parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(
        prog="plcsim",
        description="A teaching simulator of an S7-1200 PLC driving virtual training rigs, with graded exercises.",
        epilog="Exercises are named by textbook number (4.3.6) or slug (conveyor-2); `plcsim list` shows them.",
    )
    p.add_argument("--version", action="version", version=f"plcsim {_version()}")
    sub = p.add_subparsers(dest="command", metavar="COMMAND")

    lister = sub.add_parser("list", help="list the exercises with their titles", description="List the exercises.")
    lister.add_argument(
        "--exercises", metavar="PATH", help="list an instructor's exercises: a file or a folder of them"
    )
    lister.add_argument(
        "--profiles",
        action="store_true",
        help="list the CPU profiles (memory areas, tasks, restarts) and the front ends whose programs run on each",
    )

    show = sub.add_parser(
        "show",
        help="show an exercise as a student reads it: task, I/O table, scenarios, requirements and checks",
        description="Show an exercise's task, I/O table, data blocks, scenarios, the task's requirements with the "
        "checks that grade each, and the other checks: what a student needs. Instructors add --solutions.",
    )
    show.add_argument("exercise", help="textbook number (4.3.6), slug, or an exercise file")
    which = show.add_mutually_exclusive_group()
    which.add_argument(
        "--solutions",
        action="store_true",
        help="for instructors: also the shipped programs, what each shows, and the exercise's notes",
    )
    which.add_argument("--no-solutions", action="store_true", help="the student's view (the default)")
    show.add_argument(
        "--ladder",
        nargs="?",
        const="reference",
        metavar="SOLUTION",
        help="draw a shipped solution (default: the reference) as LAD networks, as the textbook's figures show it",
    )
    show.add_argument("-o", "--output", metavar="OUT.svg", help="with --ladder: where to write it (.svg or .png)")

    ladder = sub.add_parser(
        "ladder",
        help="draw a .py program as LAD networks (SVG, or PNG)",
        description="Draw each network of a Python program as ladder rungs, as the course and TIA Portal show them.",
    )
    ladder.add_argument("file", help="the program (.py)")
    ladder.add_argument("-o", "--output", metavar="OUT.svg", help="where to write it (.svg or .png); default FILE.svg")
    ladder.add_argument(
        "--exercise", metavar="EXERCISE", help="the exercise whose tags the program uses (tells coils from MOVEs)"
    )

    reference = sub.add_parser(
        "reference",
        help="print the one-page reference of every instruction and name a program can use (Markdown)",
        description="The PLC subset's instructions, declarations, types and builtins, from their docstrings.",
    )
    reference.add_argument("--output", metavar="OUT.md", help="write the page to a file instead of printing it")

    run = sub.add_parser(
        "run",
        help="run a program on an exercise's rig or a bare rig",
        description="Run a program against a rig and print a summary; on an exercise, also grade the run.",
    )
    run.add_argument(
        "target", help=f"an exercise (4.3.7, or an exercise file) or a rig ({', '.join(rig_names()) or 'none'})"
    )
    which = run.add_mutually_exclusive_group()
    which.add_argument(
        "--program",
        metavar="FILE",
        help="the PLC program to run (.py; .il for the Tecomat); on a bare rig, none runs it by hand, outputs off",
    )
    which.add_argument("--reference", action="store_true", help="run the exercise's shipped reference solution")
    which.add_argument("--solution", metavar="NAME", help="run a shipped solution by name (see `plcsim show`)")
    run.add_argument(
        "--scenario",
        metavar="NAME",
        help="which scenario of the exercise (default: the first), or a saved live session: .toml, or .py (a .py "
        "file is run as Python: trusted code only, like an exercise file; prefer .toml for a page's or a student's)",
    )
    run.add_argument("--seconds", type=float, metavar="N", help="simulated seconds (default: the scenario's)")
    run.add_argument("--seed", type=int, help="seed of placement noise and timing (default 1, or the saved session's)")
    run.add_argument(
        "--realtime",
        nargs="?",
        const=1.0,
        type=float,
        metavar="FACTOR",
        help="pace the run to the wall clock × FACTOR (default 1; 0.5 = half speed)",
    )
    run.add_argument("--rrd", metavar="OUT.rrd", help="write a rerun recording (open it with: rerun OUT.rrd)")
    run.add_argument("--plot", metavar="OUT.png", help="write a timing diagram of the run")
    run.add_argument(
        "--trace", metavar="OUT.npz", help="write the trace as named numpy columns: np.load(F)['table']['S1']"
    )
    run.add_argument("--signals", metavar="A,B,C", help="signals for --plot (default: inputs and outputs)")
    run.add_argument("--spawn-viewer", action="store_true", help="open the rerun viewer on the recording")
    run.add_argument("--cycle", metavar="TIME", help="OB1 cycle time, e.g. 1ms or 100ms (overrides the exercise)")

    grade = sub.add_parser(
        "grade",
        help="grade a submission (or a folder of them) on every scenario of an exercise",
        description="Grade PLC programs: every scenario × every check, in a sandboxed child process.",
    )
    grade.add_argument("exercise", help="textbook number (4.3.6), slug, or an exercise file (my_course/runon.py)")
    grade.add_argument("submission", nargs="?", help="a program file or a folder of them (.py, .il)")
    grade.add_argument("--reference", action="store_true", help="grade the shipped reference solution")
    grade.add_argument("--solution", metavar="NAME", help="grade a shipped solution by name")
    grade.add_argument("--seed", type=int, default=1, help="scenario seed (instructors: use a secret one)")
    grade.add_argument("--json", metavar="OUT", help="write the report as JSON (a folder for a batch)")
    grade.add_argument("--junit", metavar="OUT", help="write the report as JUnit XML")
    grade.add_argument(
        "--gradescope",
        metavar="OUT",
        help="write Gradescope's results.json (a folder for a batch: OUT/<student>/results.json)",
    )
    grade.add_argument(
        "--gradescope-visibility",
        default="visible",
        choices=("hidden", "after_due_date", "after_published", "visible"),
        help="when students see the Gradescope tests (default visible)",
    )
    grade.add_argument(
        "--rrd", metavar="DIR", help="write a rerun recording per scenario into DIR (a batch: DIR/<student>/)"
    )
    grade.add_argument(
        "--plots",
        metavar="DIR",
        help="write a timing diagram and the ladder at that scan per failed check into DIR (a batch: DIR/<student>/)",
    )
    grade.add_argument(
        "--jobs", type=int, default=1, metavar="N", help="grade N submissions at a time (batch: threads or workers)"
    )
    grade.add_argument(
        "--executor",
        default="local",
        type=_executor,
        metavar="WHERE",
        help="where a batch is graded: local (default, --jobs threads here), dask (a Dask cluster of --jobs "
        "worker processes on this machine) or dask://HOST:PORT (an existing Dask scheduler; pip install "
        "'plcsim[cluster]')",
    )
    grade.add_argument("--gradebook", metavar="OUT.csv", help="write one CSV row per submission (batch)")
    grade.add_argument("--cpu-seconds", type=int, default=60, help="CPU-time limit per submission, > 0 (default 60)")
    grade.add_argument("--memory-mb", type=int, default=2048, help="memory limit per submission, >= 64 (default 2048)")
    grade.add_argument(
        "--no-budget",
        action="store_true",
        help="a batch: no CPU budget fitted to the reference (10x its CPU time, 'too slow' over it), "
        "only --cpu-seconds (a single file is never given a fitted budget)",
    )
    grade.add_argument("--no-sandbox", action="store_true", help="grade in this process (trusted code only)")
    told = grade.add_mutually_exclusive_group()
    told.add_argument("-v", "--verbose", action="store_true", help="every check of every scenario, and why it passed")
    told.add_argument("-q", "--quiet", action="store_true", help="the verdict and the failed checks' names alone")
    _add_mutate_parser(sub)
    _add_live_parser(sub)
    _add_instructor_parsers(sub)
    return p


def _add_instructor_parsers(sub: Any) -> None:
    checker = sub.add_parser(
        "check-exercise",
        help="check an exercise's own programs: the reference passes on every seed, each wrong one fails its fails=",
        description="Grade every program an exercise ships on seeds 1..N (in this process: they are the "
        "instructor's): the reference and the correct alternatives must pass every check on every seed, each wrong "
        "solution must fail the checks its fails= names. Exit code 1 if one does not; run it on a course in CI.",
    )
    checker.add_argument("exercise", nargs="+", help="exercise files, folders of them, numbers or slugs")
    checker.add_argument("--seeds", type=int, default=3, metavar="N", help="grade on seeds 1..N (default 3)")
    drawer = sub.add_parser(
        "draw",
        help="draw a rig (or an exercise's rig) as a PNG: its layout, the drawing the recordings use",
        description="Draw a rig at rest, as the recordings draw it: belts, sensors, pistons, bins, stations.",
    )
    drawer.add_argument("rig", help=f"a rig ({', '.join(rig_names()) or 'none'}) or an exercise (number, file)")
    drawer.add_argument("-o", "--output", metavar="OUT.png", required=True, help="the PNG to write")


def _add_live_parser(sub: Any) -> None:
    live = sub.add_parser(
        "live",
        help="run a program live in the browser: press buttons, place parts, inject faults, watch tags",
        description="Serve a live operator panel on a local page. What you do is recorded as a scenario: save it "
        "(--save-scenario) and `plcsim run TARGET --program FILE --scenario SAVED` replays it bit for bit.",
    )
    live.add_argument("target", help="an exercise (4.3.7, a slug or an exercise file) or a rig (PANEL, CONV1 ...)")
    live.add_argument(
        "--program", metavar="FILE.py", help="the PLC program to run (none: operate the rig by hand, outputs off)"
    )
    live.add_argument("--scenario", metavar="NAME", help="start from this scenario of the exercise (default: none)")
    live.add_argument("--seed", type=int, default=1, help="seed of placement noise and timing (default 1)")
    live.add_argument("--port", type=int, default=8765, help="local port of the page (default 8765; 0: any free one)")
    live.add_argument(
        "--save-scenario",
        metavar="OUT.toml|OUT.py",
        help="save the session as a scenario here (.toml replays exactly; .py is Python, run by `plcsim run`)",
    )
    live.add_argument("--rrd", metavar="OUT.rrd", help="write the session's rerun recording when it ends")
    live.add_argument(
        "--speed", default="1", metavar="X", help="simulated s per wall s, 0.1 ... 10, or max (default 1)"
    )
    live.add_argument("--paused", action="store_true", help="start paused (then: one scan at a time, or run)")
    live.add_argument("--no-browser", action="store_true", help="do not open the page in the browser")


def _add_mutate_parser(sub: Any) -> None:
    mutate = sub.add_parser(
        "mutate",
        help="mutation-test an exercise's checks: which slips in the reference do they miss?",
        description="Derive mutants from the exercise's reference solution (negated contacts, forgotten contacts, "
        "swapped timers, removed edges, presets off by a step, swapped or dropped networks ...), grade each, list "
        "the survivors.",
    )
    mutate.add_argument("exercise", help="textbook number (4.3.6) or slug")
    mutate.add_argument("--seeds", type=int, default=3, metavar="N", help="grade each mutant on seeds 1..N (default 3)")
    mutate.add_argument(
        "--jobs",
        type=int,
        default=1,
        metavar="J",
        help="grade J mutants at a time (forked workers on Linux; one at a time elsewhere)",
    )
    mutate.add_argument("--json", metavar="OUT", help="write every mutant and its outcome as JSON")


def _version() -> str:

    return version.__version__


def main(argv: list[str] | None = None) -> int:
    from plcsim.core.safe_output import make_streams_safe

    make_streams_safe()  # a cp1252 console must not turn a printed ✓ into exit code 1
    args = _parser().parse_args(argv)
    if args.command is None:
        _parser().print_help()
        return EXIT_USAGE
    try:
        commands = {
            "list": _list,
            "show": _show,
            "ladder": _ladder,
            "reference": _reference,
            "run": _run,
            "grade": _grade,
            "mutate": _mutate,
            "live": _live,
            "check-exercise": _check_exercise,
            "draw": _draw,
        }
        return commands[args.command](args)
    except PlcError as exc:
        from rich.console import Console
        from rich.text import Text

        from plcsim.core.untrusted_text import for_terminal

        shown = for_terminal(str(exc), newlines=True)  # it may quote a program's text
        error = Text.assemble(("error:", "bold red"), f" {shown}")  # never folded: it names files and lines
        Console(stderr=True).print(error, highlight=False, soft_wrap=True)
        return EXIT_USAGE


def _list(args: argparse.Namespace) -> int:
    from rich.console import Console
    from rich.markup import escape

    from plcsim.exercise.catalog import all_exercises, broken_exercises, load_path
    from plcsim.grading.terminal import print_exercise_list

    if args.profiles:
        from plcsim.apps.listing import print_profiles

        print_profiles()
        return 0
    if args.exercises:
        loaded, broken = load_path(args.exercises)
        print_exercise_list(loaded, title=f"exercises in {args.exercises}")
    else:
        loaded, broken = list(all_exercises()), list(broken_exercises())
        print_exercise_list(loaded)
    for bad in broken:  # the message is text, not markup: "DATA.arr[2]" must print as it is
        Console(stderr=True).print(f"[bold red]not loaded:[/] {escape(str(bad))}", highlight=False, soft_wrap=True)
    return EXIT_USAGE if broken else 0


def _show(args: argparse.Namespace) -> int:
    from plcsim.exercise.catalog import get
    from plcsim.grading.terminal import print_exercise

    exercise = get(args.exercise)
    if args.ladder:
        from plcsim.ladder.view import Ladder

        solution = exercise.solution(args.ladder)
        if solution.path.suffix != ".py":
            raise ConfigurationError(
                f"{solution.path.name} is an instruction list; the ladder view draws Python programs (.py)"
            )
        picture = Ladder.from_file(solution.path, exercise.tag_table())
        picture.title = f"{exercise.number} {exercise.title}: {solution.name}"
        default = f"{exercise.number.replace('.', '_')}-{solution.name}.svg"
        return _write_ladder(picture, Path(args.output or default))
    print_exercise(exercise, solutions=args.solutions)
    return 0


def _ladder(args: argparse.Namespace) -> int:
    from plcsim.ladder.view import Ladder

    table = None
    if args.exercise:
        from plcsim.exercise.catalog import get

        table = get(args.exercise).tag_table()
    path = Path(args.file)
    if path.suffix != ".py":
        raise ConfigurationError(f"{path}: the ladder view draws Python programs (.py); an .il program is a list")
    return _write_ladder(Ladder.from_file(path, table), Path(args.output or path.with_suffix(".svg").name))


def _write_ladder(picture: Any, out: Path) -> int:
    """Write a ladder picture as SVG or PNG (by the file's suffix) and say where."""
    out.parent.mkdir(parents=True, exist_ok=True)
    if out.suffix.lower() == ".png":
        out.write_bytes(picture.png())
    else:
        out.write_text(picture.svg(), encoding="utf-8")
    print(f"wrote {out}")
    return 0


def _reference(args: argparse.Namespace) -> int:
    from plcsim.frontends.python.reference import instruction_reference

    page = instruction_reference()
    if args.output:
        Path(args.output).parent.mkdir(parents=True, exist_ok=True)
        Path(args.output).write_text(page, encoding="utf-8")
    else:
        sys.stdout.write(page)
    return 0


def _run(args: argparse.Namespace) -> int:
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
            program = _shipped(exercise, args.solution).program()
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
    _print_verdicts(results, console)
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


def _print_verdicts(results: list[Any], console: Any) -> None:
    from rich.text import Text

    from plcsim.core.untrusted_text import for_terminal

    for check, verdict in results:
        mark = ("✓", "green") if verdict.passed else ("✗", "red")
        message = for_terminal(verdict.message, newlines=True).replace("\n", "\n      ")
        said = "" if verdict.passed else f"\n      {message}"
        console.print(Text.assemble("  ", mark, f" {for_terminal(check.title)}{said}"), highlight=False)


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


def _executor(spec: str) -> str:
    """``--executor``: refused with the usage message, before anything is graded, if misspelt."""
    from plcsim.grading.executors import parse_executor

    try:
        parse_executor(spec)
    except PlcError as exc:
        raise argparse.ArgumentTypeError(str(exc)) from None
    return spec


def _grade(args: argparse.Namespace) -> int:
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
        target = _shipped(exercise, args.solution).path
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
        return _exit_code(reports)
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
    return _exit_code([report])


def _live(args: argparse.Namespace) -> int:
    import webbrowser

    from rich.console import Console

    from plcsim.apps.live.server import open_live
    from plcsim.apps.live.session import NO_PROGRAM

    console = Console()
    if args.save_scenario and not args.save_scenario.endswith((".toml", ".py")):
        raise PlcError(f"--save-scenario {args.save_scenario}: save as .toml (exact replay) or .py (a scenario)")
    panel = open_live(
        args.target,
        args.program or NO_PROGRAM,
        scenario=args.scenario,
        seed=args.seed,
        port=args.port,
        speed=_speed(args.speed),
        paused=args.paused,
        save_scenario=args.save_scenario,
    )
    console.print(f"live panel of {panel.session.target.name}: [bold]{panel.url}[/]  (Ctrl-C or 'End session' ends it)")
    if not args.no_browser:
        webbrowser.open(panel.url)
    try:
        while not panel.runner.finished.wait(0.5):
            pass
    except KeyboardInterrupt:
        console.print("ending the session")
    panel.stop()
    session = panel.session
    saved = panel.runner.save()
    ran = f"simulated {saved['t_ns'] / 1e9:g} s, {len(session.recorded)} actions"
    console.print(f"{ran}; trace digest {saved['digest'][:16]}")
    if saved["path"]:
        console.print(f"scenario: {saved['path']}  (replay: {session.recording().replay_command()})", highlight=False)
    if args.rrd:
        Path(args.rrd).parent.mkdir(parents=True, exist_ok=True)
        console.print(f"recording: {session.write_rrd(args.rrd)}  (open it with: rerun {args.rrd})", highlight=False)
    _print_verdicts(session.grade(), console)
    return 0


def _speed(text: str) -> float | None:
    """``--speed``: a factor from 0.1 to 10, or ``max`` (None: as fast as possible)."""
    if text.strip().lower() == "max":
        return None
    try:
        speed = float(text)
    except ValueError:
        speed = 0.0
    if not 0.1 <= speed <= 10:
        raise PlcError(f"--speed {text}: give a factor from 0.1 to 10, or max")
    return speed


def _shipped(exercise: Any, name: str | None) -> Any:
    """A shipped solution by name, or the reference; a clear error where the exercise ships none."""
    if name:
        return exercise.solution(name)
    if not any(s.kind == "reference" for s in exercise.solutions):
        raise PlcError(f"exercise {exercise.number} ships no reference solution; run yours with --program FILE.py")
    return exercise.reference


def _exit_code(reports: list[Any]) -> int:
    """0 if every submission passed, EXIT_GRADER if a grade is void through the grader's fault, else 1."""
    if any(r.grader_failed for r in reports):
        return EXIT_GRADER
    return 0 if all(r.passed for r in reports) else EXIT_FAILED


def _check_exercise(args: argparse.Namespace) -> int:
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


def _draw(args: argparse.Namespace) -> int:
    from plcsim.trace.drawing import save_rig_drawing

    if is_rig(args.rig):
        plant = rig(args.rig)()
    else:
        from plcsim.exercise.catalog import get

        exercise = get(args.rig)
        if exercise.rig is None:
            raise PlcError(f"exercise {exercise.number} has no rig to draw (it runs on the CPU alone)")
        plant = exercise.rig()
    Path(args.output).parent.mkdir(parents=True, exist_ok=True)
    print(f"drawing of {plant.name}: {save_rig_drawing(plant, args.output)}")
    return 0


def _mutate(args: argparse.Namespace) -> int:
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


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
