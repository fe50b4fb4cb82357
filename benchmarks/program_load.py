"""Loading a very large program: the subset check, the declarations and the compiler stay linear.

* ``plc_load_80k_lines_s`` -- ``CPU(program=...)`` of a generated 80 000-line file (16 000 networks of
  four lines and a blank, all in OB1): parse, subset check, module-level evaluation, analysis,
  rewriting, merging and ``exec``. Issue 9 found the subset check quadratic (a set built per name);
  a student's file is a few hundred lines, so this is the stress figure, best of the repeats.
"""

from __future__ import annotations

import gc
import time
from collections.abc import Iterator

from benchmarks.harness import Figure, Settings, figure, progress

NETWORK = "def n{k}(t):\n    if t.TL:\n        t.X = t.X + 1\n    t.LED = t.X > 3\n\n"


def large_program(networks: int) -> str:
    """A program of ``networks`` networks of five lines each, listed in OB1."""
    body = "".join(NETWORK.format(k=k) for k in range(networks))
    return "X = Int(0)\n" + body + "OB1 = [" + ", ".join(f"n{k}" for k in range(networks)) + "]\n"


def load_seconds(source: str, repeats: int) -> list[float]:
    from plcsim import CPU, Tag

    tags = {"TL": Tag("%I0.0"), "LED": Tag("%Q0.0")}
    times = []
    for _ in range(repeats):
        gc.collect()
        t0 = time.perf_counter()
        CPU(tags=tags, program=source)
        times.append(time.perf_counter() - t0)
    return sorted(times)


def run(settings: Settings) -> Iterator[Figure]:
    networks = settings.size(16_000, 200)
    source = large_program(networks)
    lines = source.count("\n")
    progress(f"load: {settings.repeats} x a {lines}-line program")
    times = load_seconds(source, settings.repeats)
    yield figure(
        "plc_load_80k_lines_s",
        round(times[0], 3),
        "s",
        median=round(times[len(times) // 2], 3),
        stat="best",
        repeats=settings.repeats,
        lines=lines,
        networks=networks,
    )
