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

from plcsim.apps.cli import describe, grade, instructor, live, run
from plcsim.apps.cli.exits import EXIT_FAILED, EXIT_GRADER, EXIT_USAGE, exit_code
from plcsim.apps.cli.parser import build_parser
from plcsim.core.errors import PlcError

__all__ = ["EXIT_FAILED", "EXIT_GRADER", "EXIT_USAGE", "build_parser", "exit_code", "main"]

COMMANDS = {
    "list": describe.list_command,
    "show": describe.show_command,
    "ladder": describe.ladder_command,
    "reference": describe.reference_command,
    "draw": describe.draw_command,
    "run": run.run_command,
    "grade": grade.grade_command,
    "mutate": instructor.mutate_command,
    "live": live.live_command,
    "check-exercise": instructor.check_exercise_command,
}
"""Each command's function: it takes the parsed arguments and returns the exit code."""


def main(argv: list[str] | None = None) -> int:
    """Run the command ``argv`` names (default: the process's arguments); its exit code."""
    from plcsim.core.safe_output import make_streams_safe

    make_streams_safe()  # a cp1252 console must not turn a printed ✓ into exit code 1
    args = build_parser().parse_args(argv)
    if args.command is None:
        build_parser().print_help()
        return EXIT_USAGE
    try:
        return COMMANDS[args.command](args)
    except PlcError as exc:
        from rich.console import Console
        from rich.text import Text

        from plcsim.core.untrusted_text import for_terminal

        shown = for_terminal(str(exc), newlines=True)  # it may quote a program's text
        error = Text.assemble(("error:", "bold red"), f" {shown}")  # never folded: it names files and lines
        Console(stderr=True).print(error, highlight=False, soft_wrap=True)
        return EXIT_USAGE
