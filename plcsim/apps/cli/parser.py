"""The ``plcsim`` command's arguments: one subparser per command, with the help a user reads."""

from __future__ import annotations

import argparse
from typing import Any

from plcsim.core import version
from plcsim.core.errors import PlcError
from plcsim.core.registry import rig_names


def build_parser() -> argparse.ArgumentParser:
    """Every command's arguments and help (the docs site prints this help too)."""
    p = argparse.ArgumentParser(
        prog="plcsim",
        description="A teaching simulator of an S7-1200 PLC driving virtual training rigs, with graded exercises.",
        epilog="Exercises are named by textbook number (4.3.6) or slug (conveyor-2); `plcsim list` shows them.",
    )
    p.add_argument("--version", action="version", version=f"plcsim {version.__version__}")
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


def _executor(spec: str) -> str:
    """``--executor``: refused with the usage message, before anything is graded, if misspelt."""
    from plcsim.grading.executors import parse_executor

    try:
        parse_executor(spec)
    except PlcError as exc:
        raise argparse.ArgumentTypeError(str(exc)) from None
    return spec
