"""Co-simulation figures: CONV1 under the reference program of 4.3.5 against the same plant stepped alone.

Workload: 60 s simulated, parts loaded at S1 one after another (the operator removes each at S2 after
1 s and loads the next 1–2 s later), 1 ms scan, 1 ms physics, the trace on (one row per scan, plant
geometry at 25 Hz). Fast-forward is off, so every physics step is taken in both runs.

"Physics alone" replays, on a fresh plant and in the same process, exactly the plant calls the
co-simulation made (actuator commands, parts placed and removed) at the same simulated times, and steps
it at the same dt: the difference between the two is what the PLC, the wiring, the scenario and the
trace cost. Budgets: ≥ 100× real time for the co-simulation; co-simulation ≤ 2× physics alone.
"""

from __future__ import annotations

import time
from collections.abc import Iterator
from typing import Any

from benchmarks.harness import Settings, figure, progress

SIM_S = 60
PLANT_CALLS = ("actuate", "place", "remove", "hold", "release", "knock_off", "operate")


def _scenario(seconds: int) -> Any:
    from plcsim.scenario import Scenario, after_event, held, place, remove

    parts = seconds // 7 + 1
    actions = [place("p1", at="S1", t="0.3s..0.8s")]
    for k in range(1, parts + 1):
        actions.append(remove(f"p{k}", when=held("S2", "1s")))
        actions.append(place(f"p{k + 1}", at="S1", when=after_event("part removed", f"p{k}"), delay="1s..2s"))
    return Scenario("shuttle", *actions, duration=f"{seconds}s")


def _cosim(seconds: int) -> tuple[float, Any, list[tuple[int, str, tuple, dict]]]:
    from exercises import get

    exercise = get("4.3.5")
    sim = exercise.simulation(exercise.reference.program(), _scenario(seconds), seed=1)
    sim.fast_forward = False
    plant = sim.plant
    log: list[tuple[int, str, tuple, dict]] = []
    for name in PLANT_CALLS:
        method = getattr(plant, name)

        def logged(*args: Any, _m: Any = method, _n: str = name, **kwargs: Any) -> Any:
            log.append((plant.now_ns, _n, args, kwargs))
            return _m(*args, **kwargs)

        setattr(plant, name, logged)
    t0 = time.perf_counter()
    sim.run()
    return time.perf_counter() - t0, sim, log


def _physics_alone(seconds: int, log: list[tuple[int, str, tuple, dict]], dt_ns: int) -> float:
    from plants import Conv1

    plant = Conv1()
    plant.reset(seed=1)
    end = seconds * 1_000_000_000
    calls = sorted(log, key=lambda e: e[0])
    k = 0
    t0 = time.perf_counter()
    while plant.now_ns < end:
        while k < len(calls) and calls[k][0] <= plant.now_ns:
            _, name, args, kwargs = calls[k]
            getattr(plant, name)(*args, **kwargs)
            k += 1
        plant.step(dt_ns)
        plant.events.clear()
    return time.perf_counter() - t0


def run(settings: Settings) -> Iterator[dict[str, Any]]:
    seconds = settings.size(SIM_S, 5)
    best_co, best_ph, scans, rows = float("inf"), float("inf"), 0, 0
    for _ in range(settings.repeats):
        wall, sim, log = _cosim(seconds)
        phys = _physics_alone(seconds, log, sim.dt_ns)
        best_co, best_ph = min(best_co, wall), min(best_ph, phys)
        scans, rows = sim.cpu.scan_count, len(sim.trace)
        progress(f"cosim {wall:.2f} s, physics alone {phys:.2f} s")
    steps = seconds * 1000
    context = {"plant": "CONV1", "program": "4.3.5 reference", "simulated_s": seconds, "scan_ms": 1,
               "physics_ms": 1, "trace_rows": rows, "scans": scans, "repeats": settings.repeats, "stat": "best"}
    yield figure("cosim_realtime_factor", round(seconds / best_co, 1), "x", budget=">= 100", **context)
    yield figure("cosim_us_per_step", round(best_co / steps * 1e6, 2), "us/step", **context)
    yield figure("physics_alone_realtime_factor", round(seconds / best_ph, 1), "x", **context)
    yield figure("physics_alone_us_per_step", round(best_ph / steps * 1e6, 2), "us/step", **context)
    yield figure("cosim_vs_physics_ratio", round(best_co / best_ph, 2), "x", budget="<= 2", **context)
