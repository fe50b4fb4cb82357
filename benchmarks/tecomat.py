"""Group ``tecomat``: the Tecomat NS950 controller alone on the 25-network workload, beside the S7 CPU.

Figures:

* ``tecomat_scans_per_s`` -- program cycles per second of wall time of ``benchmarks/workload.il`` (the
  workload network by network in instruction list), best of ``--repeats`` runs, driven exactly as the
  ``plc`` group drives the S7 CPU (same input schedule through ``cpu.inputs``, same scan budget). The S7
  figure of the same run is in ``s7_scans_per_s``, and their ratio (the figure a busy machine changes
  least) in ``ratio_to_s7``; ``load_1min`` is the machine's load when it was taken. Budget (issue 15):
  >= 50 k scans/s. The workload is P0 alone and straight, so each cycle is one generated call (issue 29).
* ``tecomat_assemble_ms`` -- assembling and linking the workload into a fresh controller.
* ``tecomat_assemble_defs_data_ms`` -- assembling ``n`` ``#def`` constants and ``n`` ``#data`` items that
  name them (issue 26: each item re-evaluated every ``#def`` before, quadratic); ``per_item_us`` at ``n``
  and at ``n/4`` stay close when the assembler is linear.
"""

from __future__ import annotations

import gc
import os
import time
from collections.abc import Iterator
from pathlib import Path

from benchmarks import plc, workload
from benchmarks.harness import Figure, Settings, drive, figure, measure, progress

SOURCE = (Path(__file__).parent / "workload.il").read_text(encoding="utf-8")


def new_controller():
    from plcsim.controllers.choice import controller_for
    from plcsim.frontends.il import program_text

    return controller_for(program_text(SOURCE, "workload.il"), workload.tags())


def _run_once(n: int, max_s: float, sched: list) -> tuple[int, float]:
    cpu = new_controller()
    return drive(cpu.inputs.update, cpu.scan, sched, n, max_s)


def run(settings: Settings) -> Iterator[Figure]:
    n = settings.size(200_000, 2_000)
    max_s = settings.size(plc.MAX_S, 2.0)
    sched = workload.build_schedule(n)
    progress(f"tecomat: {settings.repeats} x {n} scans")
    rates = measure(lambda k, s: _run_once(k, s, sched), n, max_s, settings.repeats)
    s7, _, _ = plc.throughput(settings)
    yield figure(
        "tecomat_scans_per_s",
        round(rates.best),
        "scans/s",
        median=round(rates.median),
        s7_scans_per_s=round(s7.best),
        ratio_to_s7=round(rates.best / s7.best, 3),
        load_1min=round(os.getloadavg()[0], 2) if hasattr(os, "getloadavg") else None,  # not on Windows
        stat="best",
        repeats=settings.repeats,
        scans=rates.best_scans,
        networks=workload.NETWORKS,
        instructions=SOURCE.count("\n") - sum(1 for line in SOURCE.splitlines() if line.startswith((";", "#"))),
    )
    times = []
    for _ in range(max(settings.repeats, 5) + 1):
        gc.collect()
        t0 = time.perf_counter()
        new_controller()
        times.append((time.perf_counter() - t0) * 1e3)
    times = sorted(times[1:])
    yield figure("tecomat_assemble_ms", round(times[0], 3), "ms", median=round(times[len(times) // 2], 3))
    n = settings.size(20_000, 400)
    small, large = _assemble_defs_data_ms(n // 4), _assemble_defs_data_ms(n)
    yield figure(
        "tecomat_assemble_defs_data_ms",
        round(large, 1),
        "ms",
        defs=n,
        items=n,
        per_item_us=round(1e3 * large / n, 2),
        per_item_us_at_quarter=round(1e3 * small / (n // 4), 2),
    )


def _assemble_defs_data_ms(n: int) -> float:
    """The best of three assemblies of ``n`` #def constants and ``n`` #data items naming them, in ms."""
    from plcsim.controllers.tecomat.assembler import assemble

    source = "".join(f"#def KON{k} {k % 100}\n" for k in range(n))
    source += "".join(f"#data byte TAB{k} = KON{k}, 1\n" for k in range(n)) + "LD X0.0\nWR Y0.0\n"
    best = float("inf")
    for _ in range(3):
        t0 = time.perf_counter()
        assemble(source, "defs.il")
        best = min(best, (time.perf_counter() - t0) * 1e3)
    return best
