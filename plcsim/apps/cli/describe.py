"""The commands that describe without simulating: list, show, ladder, reference, draw."""

from __future__ import annotations

import argparse
import sys
from pathlib import Path
from typing import Any

from plcsim.apps.cli.exits import EXIT_USAGE
from plcsim.core.errors import ConfigurationError, PlcError
from plcsim.core.registry import is_rig, rig


def list_command(args: argparse.Namespace) -> int:
    """``plcsim list``: the exercises (built in, or an instructor's file or folder), or the CPU profiles."""
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


def show_command(args: argparse.Namespace) -> int:
    """``plcsim show``: an exercise as a student reads it (``--solutions`` for instructors), or a solution's ladder."""
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


def ladder_command(args: argparse.Namespace) -> int:
    """``plcsim ladder``: a .py program drawn as LAD networks."""
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


def reference_command(args: argparse.Namespace) -> int:
    """``plcsim reference``: the one-page instruction reference, printed or written."""
    from plcsim.frontends.python.reference import instruction_reference

    page = instruction_reference()
    if args.output:
        Path(args.output).parent.mkdir(parents=True, exist_ok=True)
        Path(args.output).write_text(page, encoding="utf-8")
    else:
        sys.stdout.write(page)
    return 0


def draw_command(args: argparse.Namespace) -> int:
    """``plcsim draw``: a rig at rest, drawn as the recordings draw it."""
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
