"""Live panel figures: how fast a live session can run, and what one frame of the page costs.

* ``live_max_speed`` — simulated seconds per wall second of a session run "as fast as possible" the way the
  server runs it (20 ms frames, each ending at its deadline, a state snapshot after each), on PANEL (a lamp
  program, quiescent plant: 1 ms scans, 3 s of wall time) and on CONV1 (4.3.5's reference, a part riding the belt
  from S1 for the first 4.5 simulated s, before it reaches S2: every 1 ms physics step is taken). Budget: ≥ 10 (the
  page's top speed, ×10) on both.
* ``live_frame_ms`` — one state snapshot of the page (moving shapes, watch table, logs) as JSON, on CONV1.
"""

from __future__ import annotations

import json
import time
from collections.abc import Iterator
from typing import Any

from benchmarks.harness import Settings, figure, progress

FRAME_S = 0.02


def _session(rig: str) -> Any:
    from exercises import get
    from plcsim.apps.live import LiveSession
    from plcsim.apps.live.session import PANEL_DEMO

    if rig == "PANEL":
        return LiveSession("PANEL", PANEL_DEMO, seed=1)
    session = LiveSession("CONV1", str(get("4.3.5").reference.path), seed=1)
    session.do("place", station="S1")
    return session


def run(settings: Settings) -> Iterator[dict[str, Any]]:
    from plcsim.apps.live.runner import Runner

    wall_s = 0.3 if settings.quick else 3.0
    riding_ns = 500_000_000 if settings.quick else 4_500_000_000
    for rig in ("PANEL", "CONV1"):
        rates = []
        for _ in range(settings.repeats):
            runner = Runner(_session(rig), speed=None)
            t0 = time.perf_counter()
            while time.perf_counter() - t0 < wall_s and (rig == "PANEL" or runner.session.now < riding_ns):
                start = time.perf_counter()
                runner.tick(FRAME_S, deadline=start + FRAME_S)
                runner._take_snapshot()
            rates.append(runner.session.now / 1e9 / (time.perf_counter() - t0))
        progress(f"{rig}: {max(rates):.1f}x real time as fast as possible")
        yield figure("live_max_speed", round(max(rates), 2), "x real time", rig=rig, frame_s=FRAME_S)
    session = _session("CONV1")
    session.advance(2_000_000_000)  # the part is on the belt
    n = 20 if settings.quick else 200
    t0 = time.perf_counter()
    size = 0
    for _ in range(n):
        size = len(json.dumps(session.state()))
    ms = (time.perf_counter() - t0) / n * 1e3
    yield figure("live_frame_ms", round(ms, 3), "ms", rig="CONV1", frames=n, bytes=size)
