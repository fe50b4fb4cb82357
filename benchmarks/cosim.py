"""Co-simulation figures: each rig under a reference program against the same plant stepped alone.

The workloads, each 1 ms scan, 1 ms physics, the trace on (one row per scan, plant geometry at
25 Hz), fast-forward off so that every physics step is taken in both runs:

* ``shuttle`` (CONV1, 4.3.5's reference): 60 s, one part at a time loaded at S1, removed at S2 after 1 s.
* ``several`` (CONV1, 4.3.6's reference, its "five objects" scenario repeated): several parts on the belt
  at once, queued at S2 while the belt waits.
* ``aligner`` (ALIGN, 4.3.12's reference): 60 s, a crooked part every 4 s, pushed flat, taken away.
* ``sorter`` (SORT, 4.3.17's reference, its "six mixed" scenario): six parts of mixed colours on the belt.
* ``punch`` (PUNCH, 6.3.5's reference): 60 s of parts loaded one after the other, each shuttled twice
  to the press by the reversible belt, three strokes at each visit.
* ``hoist`` (SKIP, 4.3.16's reference, its "one AUTO cycle" scenario): 77 s, the skip filled, up fast and
  slow, 6 s at the top while its batch pours into the mixer, down slowly. ``physics_alone_us_per_step_pouring``
  is the plant alone while the batch pours (the skip standing tipped at the top), the costliest part of its cycle.
* ``crane`` (HBW, 4.3.18's reference, its "all nine places" scenario): 70 s, nine put-in requests at the HMI,
  three axes driven by set-points, a part on the fork put down on each place of the rack.

"Physics alone" replays, on a fresh plant and in the same process, exactly the plant calls the
co-simulation made (actuator commands, parts placed and removed) at the same simulated times, and steps
it at the same dt: the difference between the two is what the PLC, the wiring, the scenario and the
trace cost. Budgets: ≥ 100× real time for the co-simulation; co-simulation ≤ 2× physics alone.
``cosim_overhead_us_per_step_*`` is that difference per step (the PLC, wiring, trace and drawing), so a ratio above
budget can be told apart from a slow plant: it is ``(ratio - 1) × physics``, and the ratio grows when the physics
gets faster. For the shuttle and the sorter a third run, the hand-written baseline
(:mod:`benchmarks.handwritten`: the same program inlined by hand, reading the sensors and commanding the
actuators itself, its trace rows in a preallocated numpy array, checked equal to plcsim's trace: ``same_rows``), gives
``handwritten_overhead_us_per_step_*`` (baseline minus physics alone, per step) and
``cosim_overhead_vs_handwritten_ratio_*``, plcsim's overhead per step over the baseline's (budget <= 2).
``load_1min`` (the machine's load average as the workload ends) says how shared the cores were.
Both runs are timed in process time (``time.process_time``), not wall time: on a loaded machine the wall clock
counts the other processes' turns too, process time only this run's (the real-time factor is simulated s per
CPU s).
"""

from __future__ import annotations

import os
import time
from collections.abc import Iterator
from typing import Any

from benchmarks import handwritten
from benchmarks.harness import Settings, figure, progress

SIM_S = 60
PLANT_CALLS = (
    "actuate",
    "place",
    "remove",
    "hold",
    "release",
    "knock_off",
    "operate",
    "jam_piston",
    "set_ambient",
    "fill",
)
WORKLOADS = (
    ("shuttle", "4.3.5 reference", "CONV1"),
    ("several", "4.3.6 reference", "CONV1"),
    ("aligner", "4.3.12 reference", "ALIGN"),
    ("sorter", "4.3.17 reference", "SORT"),
    ("punch", "6.3.5 reference", "PUNCH"),
    ("hoist", "4.3.16 reference", "SKIP"),
    ("crane", "4.3.18 reference", "HBW"),
)


def _scenario(seconds: int) -> Any:
    from exercises._conveyor import shuttle
    from plcsim.scenario.planning import Scenario

    return Scenario("shuttle", *shuttle(seconds // 7 + 1), duration=f"{seconds}s")


def _aligner(seconds: int) -> Any:
    from plcsim.scenario.planning import Scenario
    from plcsim.scenario.verbs import place, remove

    actions = []
    for k in range(seconds // 4):
        pid = f"p{k + 1}"
        actions.append(place(pid, at="table", t=f"{4 * k + 0.5}s", offset_mm=(0.0, 15.0), angle_deg=(-15.0, 15.0)))
        actions.append(remove(pid, t=f"{4 * k + 3.5}s"))
    return Scenario("aligner", *actions, duration=f"{seconds}s")


def _punch(seconds: int) -> Any:
    from exercises._punch import cycles
    from plcsim.scenario.planning import Scenario

    writes = {1: {"M1_ZIADANY_POCET": 2, "M2_ZIADANY_POCET": 3}}
    return Scenario("punch", *cycles(3, writes=writes), duration=f"{seconds}s")


def _cosim(workload: str, seconds: int) -> tuple[float, Any, list[tuple[int, str, tuple, dict]]]:
    from exercises import get

    if workload == "shuttle":
        exercise, scenario = get("4.3.5"), _scenario(seconds)
    elif workload == "aligner":
        exercise, scenario = get("4.3.12"), _aligner(seconds)
    elif workload == "sorter":
        exercise = get("4.3.17")
        scenario = exercise.scenario("six mixed")
    elif workload == "punch":
        exercise, scenario = get("6.3.5"), _punch(seconds)
    elif workload == "hoist":
        exercise = get("4.3.16")
        scenario = exercise.scenario("one AUTO cycle")
    elif workload == "crane":
        exercise = get("4.3.18")
        scenario = exercise.scenario("all nine places")
    else:
        exercise = get("4.3.6")
        scenario = exercise.scenario("five objects")
    sim = exercise.simulation(exercise.reference.program(), scenario, seed=1)
    sim.fast_forward = False
    plant = sim.plant
    log: list[tuple[int, str, tuple, dict]] = []
    for name in PLANT_CALLS:
        method = getattr(plant, name, None)
        if method is None:  # not a capability of this rig
            continue

        def logged(*args: Any, _m: Any = method, _n: str = name, **kwargs: Any) -> Any:
            log.append((plant.now_ns, _n, args, kwargs))
            return _m(*args, **kwargs)

        setattr(plant, name, logged)
    t0 = time.process_time()
    sim.run()
    return time.process_time() - t0, sim, log


def _physics_alone(rig: str, seconds: int, log: list[tuple[int, str, tuple, dict]], dt_ns: int, kind: type) -> float:
    from plants import RIGS

    plant = RIGS[rig]() if rig in RIGS else kind()  # a rig the installed metadata lacks yet (before pip install -e .)
    plant.reset(seed=1)
    end = seconds * 1_000_000_000
    calls = sorted(log, key=lambda e: e[0])
    k = 0
    t0 = time.process_time()
    while plant.now_ns < end:
        while k < len(calls) and calls[k][0] <= plant.now_ns:
            _, name, args, kwargs = calls[k]
            getattr(plant, name)(*args, **kwargs)
            k += 1
        plant.step(dt_ns)
        plant.events.clear()
    return time.process_time() - t0


def run(settings: Settings) -> Iterator[dict[str, Any]]:
    for workload, program, rig in WORKLOADS:
        yield from _workload(settings, workload, program, rig)


def _workload(settings: Settings, workload: str, program: str, rig: str) -> Iterator[dict[str, Any]]:
    best_co, best_ph, best_hw, scans, rows, seconds = float("inf"), float("inf"), float("inf"), 0, 0, 0
    same: bool | None = None
    for _ in range(settings.repeats):
        wall, sim, log = _cosim(workload, settings.size(SIM_S, 5))
        seconds = sim.now // 1_000_000_000
        phys = _physics_alone(rig, seconds, log, sim.dt_ns, type(sim.plant))
        best_co, best_ph = min(best_co, wall), min(best_ph, phys)
        scans, rows = sim.cpu.scan_count, len(sim.trace)
        note = ""
        if workload in handwritten.BASELINES:
            hw_rows, hw = handwritten.run_baseline(workload, rig, seconds, log, sim.dt_ns)
            best_hw = min(best_hw, hw)
            same = handwritten.same_rows(hw_rows, sim.trace) and (same is not False)
            note = f", hand-written {hw:.2f} s"
        progress(f"{workload}: cosim {wall:.2f} s, physics alone {phys:.2f} s{note}")
    steps = seconds * 1000
    context = {
        "workload": workload,
        "plant": rig,
        "program": program,
        "simulated_s": seconds,
        "scan_ms": 1,
        "physics_ms": 1,
        "trace_rows": rows,
        "scans": scans,
        "repeats": settings.repeats,
        "stat": "best",
        "load_1min": round(os.getloadavg()[0], 2) if hasattr(os, "getloadavg") else None,  # not on Windows
    }
    yield figure(f"cosim_realtime_factor_{workload}", round(seconds / best_co, 1), "x", budget=">= 100", **context)
    yield figure(f"cosim_us_per_step_{workload}", round(best_co / steps * 1e6, 2), "us/step", **context)
    yield figure(f"physics_alone_us_per_step_{workload}", round(best_ph / steps * 1e6, 2), "us/step", **context)
    yield figure(f"cosim_vs_physics_ratio_{workload}", round(best_co / best_ph, 2), "x", budget="<= 2", **context)
    overhead = (best_co - best_ph) / steps * 1e6
    yield figure(f"cosim_overhead_us_per_step_{workload}", round(overhead, 2), "us/step", **context)
    if same is not None:
        baseline = (best_hw - best_ph) / steps * 1e6
        yield figure(
            f"handwritten_overhead_us_per_step_{workload}", round(baseline, 2), "us/step", same_rows=same, **context
        )
        yield figure(
            f"cosim_overhead_vs_handwritten_ratio_{workload}",
            round(overhead / baseline, 2) if baseline > 0 else None,
            "x",
            budget="<= 2",
            same_rows=same,
            cosim_overhead_us_per_step=round(overhead, 2),
            handwritten_overhead_us_per_step=round(baseline, 2),
            **context,
        )
    if workload == "hoist":
        pouring = min(_pouring_alone() for _ in range(settings.repeats))
        yield figure("physics_alone_us_per_step_pouring", round(pouring, 2), "us/step", **context)


def _pouring_alone(seconds: float = 2.0) -> float:
    """The skip hoist alone while a full batch pours into the mixer (µs per 1 ms step, process time)."""
    from plants.skip import Skip

    plant = Skip()
    plant.fill("skip")
    plant.winch.s = plant.bucket.position = 991.0  # where the skip stops at the top sensor
    steps = round(seconds * 1000)
    t0 = time.process_time()
    for _ in range(steps):
        plant.step(1_000_000)
    spent = time.process_time() - t0
    assert plant.bucket.bin_g > 0.0, "nothing poured"
    return spent / steps * 1e6
