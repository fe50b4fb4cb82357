"""Ladder figures: drawing a program as LAD, one monitored picture, and the live page with its Program card.

* ``ladder_draw_ms`` — reading the largest shipped Python solution as rungs and drawing it as SVG.
* ``ladder_monitor_ms`` — one online picture of it (power flow for the CPU's tags, then the SVG): what the
  Program card costs per refresh.
* ``live_max_speed_program_card`` — ``live_max_speed`` on CONV1 (see :mod:`benchmarks.live`) with the Program
  card drawn after every frame (the page asks at most every 100 ms: this is the worst case). Budget: ≥ 10.
"""

from __future__ import annotations

import time
from collections.abc import Iterator
from typing import Any

from benchmarks.harness import Settings, figure, progress
from benchmarks.live import FRAME_S, _session


def _largest() -> Any:
    """The shipped Python solution with the most statements (docstrings aside, the most to draw)."""
    import ast

    from exercises import all_exercises

    def statements(path: Any) -> int:
        tree = ast.parse(path.read_text(encoding="utf-8"))
        return sum(isinstance(node, ast.stmt) for node in ast.walk(tree))

    solutions = [(ex, s) for ex in all_exercises() for s in ex.solutions if s.path.suffix == ".py"]
    return max(solutions, key=lambda pair: statements(pair[1].path))


def run(settings: Settings) -> Iterator[dict[str, Any]]:
    from plcsim import CPU
    from plcsim.apps.live.runner import Runner
    from plcsim.frontends.python.program import Program
    from plcsim.ladder.view import Ladder

    exercise, solution = _largest()
    name = f"{exercise.number}/{solution.name}"
    n = 3 if settings.quick else 30
    best = []
    for _ in range(settings.repeats):
        t0 = time.perf_counter()
        for _ in range(n):
            svg = Ladder(Program.from_file(solution.path), exercise.tag_table()).svg()
        best.append((time.perf_counter() - t0) / n * 1e3)
    yield figure("ladder_draw_ms", round(min(best), 2), "ms", program=name, bytes=len(svg))
    program = Program.from_file(solution.path)
    ladder = Ladder(program, exercise.tag_table())
    cpu = CPU(exercise.tag_table(), program, **exercise.cpu)
    cpu.run("1s")
    best = []
    for _ in range(settings.repeats):
        t0 = time.perf_counter()
        for _ in range(n):
            ladder.monitor(cpu.t)
        best.append((time.perf_counter() - t0) / n * 1e3)
    yield figure("ladder_monitor_ms", round(min(best), 2), "ms", program=name)
    wall_s = 0.3 if settings.quick else 3.0
    riding_ns = 500_000_000 if settings.quick else 4_500_000_000
    rates = []
    for _ in range(settings.repeats):
        runner = Runner(_session("CONV1"), speed=None)
        t0 = time.perf_counter()
        while time.perf_counter() - t0 < wall_s and runner.session.now < riding_ns:
            start = time.perf_counter()
            runner.tick(FRAME_S, deadline=start + FRAME_S)
            runner._take_snapshot()
            runner.session.ladder_svg()
        rates.append(runner.session.now / 1e9 / (time.perf_counter() - t0))
    progress(f"CONV1 with the Program card: {max(rates):.1f}x real time")
    yield figure("live_max_speed_program_card", round(max(rates), 2), "x real time", rig="CONV1", frame_s=FRAME_S)
