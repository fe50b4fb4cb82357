"""``python -m benchmarks [--quick] [--only GROUP ...] [--repeats N] [--seeds N ...]``: one JSON line per figure.

To add a group: write ``benchmarks/<module>.py`` with ``run(settings) -> Iterator[Figure]`` (see
:mod:`benchmarks.harness`) and add one line to :data:`GROUPS`. Groups run in the registry's order; a group
that needs another's result (the pyrung ratios need plcsim's rate) asks that group's module, which caches
it in ``settings.cache`` so it is measured once per process.
"""

from __future__ import annotations

import argparse
import importlib
import sys

from benchmarks.harness import Settings, emit, progress

GROUPS: dict[str, str] = {  # group name -> module with run(settings)
    "plc": "benchmarks.plc",
    "pyrung": "benchmarks.pyrung_peer",
    "inlined": "benchmarks.inlined",
    "equivalence": "benchmarks.equivalence",
    "cosim": "benchmarks.cosim",
    "grading": "benchmarks.grading",
    "load": "benchmarks.program_load",
    "mutation": "benchmarks.mutation",
    "recording": "benchmarks.recording",
    "live": "benchmarks.live",
    "ladder": "benchmarks.ladder",
    "tecomat": "benchmarks.tecomat",
    "mechanisms": "benchmarks.mechanisms",
    "digests": "benchmarks.digests",
}


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="python -m benchmarks", description=__doc__.splitlines()[0])
    ap.add_argument("--quick", action="store_true", help="tiny sizes, for smoke tests (figures are not meaningful)")
    ap.add_argument(
        "--only",
        action="append",
        choices=list(GROUPS),
        metavar="NAME",
        help=f"run only this group (repeatable): {', '.join(GROUPS)}",
    )
    ap.add_argument("--repeats", type=int, default=None, help="timed runs per figure (default 3, 1 with --quick)")
    ap.add_argument(
        "--seeds",
        type=int,
        nargs="+",
        default=None,
        help="seeds of group 'digests' (default 0 7; the suite's 1 2 3 prove a change on every seed it uses)",
    )
    args = ap.parse_args(argv)
    repeats = args.repeats if args.repeats is not None else (1 if args.quick else 3)
    if repeats < 1:
        ap.error("--repeats must be at least 1")
    settings = Settings(quick=args.quick, repeats=repeats, seeds=tuple(args.seeds) if args.seeds else None)
    for name in args.only or list(GROUPS):
        progress(f"== {name}")
        for fig in importlib.import_module(GROUPS[name]).run(settings):
            emit(fig)
    return 0


if __name__ == "__main__":
    sys.exit(main())
