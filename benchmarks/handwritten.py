"""Hand-written co-simulation baselines: what the shuttle and the sorter cost written by hand in Python.

For :mod:`benchmarks.cosim`: the workload's reference program inlined by hand as one loop over the physics
steps that reads the plant's sensors, runs the program's networks (timers with plcsim's S7 semantics),
commands the actuators that changed, steps the plant and stores the trace row, the values plcsim's trace
holds in the same column order, into a preallocated numpy array. The operator's actions (parts placed and
taken away) are the co-simulation's own, replayed at their times as :func:`benchmarks.cosim._physics_alone`
replays them; the actuator commands are the program's. No geometry is drawn (plcsim draws at 25 Hz).

So that the baseline is the same work, not a cheaper one, :func:`same_rows` compares its rows with the
co-simulation's trace: every value of every row must agree (``same_rows`` in the figures).
"""

from __future__ import annotations

import time
from collections.abc import Callable
from typing import Any

import numpy as np

_NS_PER_MS = 1_000_000


def _replay(plant: Any, calls: list[tuple[int, str, tuple, dict]], k: int, now: int) -> int:
    """Make the scenario's plant calls due at ``now`` (from index ``k``); returns the next index."""
    while k < len(calls) and calls[k][0] <= now:
        _, name, args, kwargs = calls[k]
        getattr(plant, name)(*args, **kwargs)
        k += 1
    return k


def shuttle(plant: Any, calls: list[tuple[int, str, tuple, dict]], end_ns: int, dt_ns: int) -> tuple[np.ndarray, float]:
    """4.3.5's reference on CONV1 (S1 -> SET D1, S2 -> RESET D1); rows ``S1, S2, D1``. Returns (rows, CPU s)."""
    steps = -(-end_ns // dt_ns)
    rows = np.zeros((steps, 3))
    sensors, events, actuate, step = plant.sensors, plant.events, plant.actuate, plant.step
    ncalls, k, i, now = len(calls), 0, 0, plant.now_ns
    d1 = sent = False
    t0 = time.process_time()
    while now < end_ns:
        if k < ncalls and calls[k][0] <= now:
            k = _replay(plant, calls, k, now)
        s1, s2 = sensors["S1"], sensors["S2"]
        if s1:
            d1 = True
        if s2:
            d1 = False
        rows[i] = (s1, s2, d1)
        step(dt_ns)
        events.clear()
        if d1 != sent:
            sent = d1
            actuate("D1", d1)
        now += dt_ns
        i += 1
    return rows[:i], time.process_time() - t0


def sorter(plant: Any, calls: list[tuple[int, str, tuple, dict]], end_ns: int, dt_ns: int) -> tuple[np.ndarray, float]:
    """4.3.17's reference on SORT, its ten rungs written out; rows in the trace's 26 columns (inputs as the
    NC wiring delivers them, outputs, DATA, each TON's Q and ET). Returns (rows, CPU s)."""
    steps = -(-end_ns // dt_ns)
    rows = np.zeros((steps, 26))
    sensors, events, actuate, step = plant.sensors, plant.events, plant.actuate, plant.step
    ncalls, k, i, now = len(calls), 0, 0, plant.now_ns
    d1 = p1 = p2 = p3 = komp = False
    o1 = o2 = o3 = o4 = o5 = False  # occupancy of positions 1..5
    typ2 = typ3 = typ4 = typ5 = 0
    in1 = in2 = in3 = run1 = run2 = run3 = q1 = q2 = q3 = False  # TON_P1..3: IN, running, Q
    start1 = start2 = start3 = et1 = et2 = et3 = 0  # start ns, ET ms
    sent = [False] * 5  # D1_VPRED, Piest1..3, Kompresor as last commanded
    names = ("D1_VPRED", "Piest1_Farba1", "Piest2_Farba2", "Piest3_Farba3", "Kompresor")
    t0 = time.process_time()
    while now < end_ns:
        if k < ncalls and calls[k][0] <= now:
            k = _replay(plant, calls, k, now)
        os1, os3, os4 = not sensors["OS1_Vstup"], not sensors["OS3_Farba1"], not sensors["OS4_Farba2"]
        os5, os2 = not sensors["OS5_Farba3"], not sensors["OS2_Detekcia"]
        farba = max(-32_768, min(32_767, round(sensors["FARBA"])))
        if not os1:  # rung 1
            o1 = True
        if d1 and not o2 and not os2:  # rung 2
            o2, o1 = True, False
            if 2000 <= farba <= 9000:
                typ2 = 1
            if 9001 <= farba <= 17000:
                typ2 = 2
            if 17001 <= farba <= 25000:
                typ2 = 3
        if d1 and not o3 and not os3:  # rung 3
            o3, o2, typ3, typ2 = True, False, typ2, 0
        if d1 and not o4 and not os4:  # rung 4
            o4, o3, typ4, typ3 = True, False, typ3, 0
        if d1 and not o5 and not os5:  # rung 5
            o5, o4, typ5, typ4 = True, False, typ4, 0
        d1 = o1 or o2 or o3 or o4 or o5  # rung 6
        komp = p1 or p2 or p3  # rung 7
        if o3 and os3 and typ3 == 1:  # rung 8
            p1 = True
        if p1:
            if not in1:
                run1, start1, et1, q1 = True, now, 0, False
            if run1:
                elapsed = (now - start1) // _NS_PER_MS
                if elapsed >= 1000:
                    run1, et1, q1 = False, 1000, True
                else:
                    et1 = elapsed if elapsed > 0 else 0
        else:
            run1, et1, q1 = False, 0, False
        in1 = p1
        if q1:
            p1, o3, typ3 = False, False, 0
        if o4 and os4 and typ4 == 2:  # rung 9
            p2 = True
        if p2:
            if not in2:
                run2, start2, et2, q2 = True, now, 0, False
            if run2:
                elapsed = (now - start2) // _NS_PER_MS
                if elapsed >= 1000:
                    run2, et2, q2 = False, 1000, True
                else:
                    et2 = elapsed if elapsed > 0 else 0
        else:
            run2, et2, q2 = False, 0, False
        in2 = p2
        if q2:
            p2, o4, typ4 = False, False, 0
        if o5 and os5 and typ5 == 3:  # rung 10
            p3 = True
        if p3:
            if not in3:
                run3, start3, et3, q3 = True, now, 0, False
            if run3:
                elapsed = (now - start3) // _NS_PER_MS
                if elapsed >= 1000:
                    run3, et3, q3 = False, 1000, True
                else:
                    et3 = elapsed if elapsed > 0 else 0
        else:
            run3, et3, q3 = False, 0, False
        in3 = p3
        if q3:
            p3, o5, typ5 = False, False, 0
        rows[i] = (
            *(os1, os3, os4, os5, os2, farba, d1, p1, p2, p3, komp, o1, o2, o3, o4, o5, typ2, typ3, typ4, typ5),
            *(q1, et1, q2, et2, q3, et3),
        )
        step(dt_ns)
        events.clear()
        for j, value in enumerate((d1, p1, p2, p3, komp)):
            if value != sent[j]:
                sent[j] = value
                actuate(names[j], value)
        now += dt_ns
        i += 1
    return rows[:i], time.process_time() - t0


BASELINES: dict[str, Callable[..., tuple[np.ndarray, float]]] = {"shuttle": shuttle, "sorter": sorter}
"""Workload name (of :data:`benchmarks.cosim.WORKLOADS`) -> its hand-written baseline."""


def run_baseline(
    workload: str, rig: str, seconds: int, log: list[tuple[int, str, tuple, dict]], dt_ns: int
) -> tuple[np.ndarray, float]:
    """The workload's baseline on a fresh plant (seed 1, as the co-simulation), replaying the scenario's calls
    of ``log`` (the actuator commands are the program's own). Returns (rows, CPU s)."""
    from plants import RIGS

    plant = RIGS[rig]()
    plant.reset(seed=1)
    calls = sorted((c for c in log if c[1] != "actuate"), key=lambda c: c[0])
    return BASELINES[workload](plant, calls, seconds * 1_000_000_000, dt_ns)


def same_rows(rows: np.ndarray, trace: Any) -> bool:
    """Whether the baseline's rows are the co-simulation trace's values, row for row."""
    table = trace.table[:, 3:]
    return table.shape == rows.shape and bool(np.array_equal(table, rows))
