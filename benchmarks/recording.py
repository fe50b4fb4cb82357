"""Recording figure: exporting a run to a rerun ``.rrd`` (:func:`plcsim.trace.rerun.export_rrd`), for
4.3.7's jam scenario (16 simulated s, 16000 scans, 7 signals, 391 geometry frames), as
``plcsim run ... --rrd`` does. The simulation is not timed, only the export; the file's size and the
rows sent are reported beside the time."""

from __future__ import annotations

import statistics
import tempfile
import time
from collections.abc import Iterator
from pathlib import Path
from typing import Any

from benchmarks.harness import Settings, figure, progress


def run(settings: Settings) -> Iterator[dict[str, Any]]:
    try:
        import rerun  # noqa: F401
    except ImportError:
        yield figure("rrd_export_s", None, "s", skipped="rerun-sdk is not installed")
        return
    from exercises import get
    from plcsim.trace.rerun import export_rrd, group_rows, signal_groups

    ex = get("4.3.7")
    sim = ex.simulation(ex.reference.program(), ex.scenario("jam"), seed=1)
    sim.run(int(1e9) if settings.quick else None)
    trace = sim.trace
    rows = sum(len(group_rows(trace, [n])[0]) for n in trace.names)
    times = []
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "run.rrd"
        for _ in range(settings.repeats):
            t0 = time.perf_counter()
            export_rrd(trace, path)
            times.append(time.perf_counter() - t0)
        size = path.stat().st_size
    progress(f"exported {len(trace)} scans in {min(times):.3f} s ({size / 1e6:.2f} MB)")
    yield figure(
        "rrd_export_s",
        round(min(times), 4),
        "s",
        median=round(statistics.median(times), 4),
        exercise="4.3.7",
        scenario="jam",
        scans=len(trace),
        signals=len(trace.names),
        lanes=sum(len(v) for g, v in signal_groups(trace).items() if g in ("inputs", "outputs", "internal")),
        frames=len(trace.frames),
        signal_rows=rows,
        rrd_bytes=size,
    )
