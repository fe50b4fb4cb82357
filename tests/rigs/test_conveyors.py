"""Conveyor rigs: nominal transport times of spec §5, stopping, open end / end stop, jams, faults, determinism.

All runs use dt = 1 ms. Times are the plant's own ``now_ns`` at the end of the step in which a beam changed.
"""

from __future__ import annotations

import ast
import contextlib
import hashlib
import io
import subprocess
import sys
from pathlib import Path

import pytest
from platforms import WINDOWS_ROOT

from plants import Conv1, Conv2x2, Conv3, StationOccupiedError

MS = 1_000_000
ROOT = Path(__file__).resolve().parents[2]


def run(plant, until_s: float, edges: list | None = None) -> list:
    """Step ``plant`` to ``until_s``; append (sensor, value, t_s) for every sensor change."""
    edges = [] if edges is None else edges
    prev = dict(plant.sensors)
    end = round(until_s * 1e9)
    while plant.now_ns < end:
        plant.step(MS)
        for k, v in plant.sensors.items():
            if v != prev[k]:
                edges.append((k, v, plant.now_ns / 1e9))
                prev[k] = v
    return edges


def rise(edges: list, name: str, n: int = 0) -> float:
    return [t for k, v, t in edges if k == name and v][n]


def kinds(plant) -> list[tuple[str, str, str | None]]:
    return [(e.kind, e.subject, e.part) for e in plant.events]


# --- nominal times (spec §5) ---------------------------------------------------------------------------------------


def test_conv1_transport_time_and_stop_at_s2():
    """Part placed centred on S1 at t = 0 with D1 switched on at S1↑ (as the reference program does, one scan later).

    Measured: S2↑ − S1↑. Geometry: the leading face goes from 55 mm to the beam edge at 294 mm (239 mm at 50 mm/s)
    plus the drive's 50 ms lag: 4.83 s; spec §5.2: 4.8 s ± 10 %.
    """
    c = Conv1()
    c.place("S1")
    edges = []
    while not c.sensors["S1"]:
        run(c, c.now_ns / 1e9 + 0.001, edges)
    t_s1 = c.now_ns / 1e9
    c.actuate("D1", True)
    while not c.sensors["S2"]:
        run(c, c.now_ns / 1e9 + 0.001, edges)
    t_s2 = c.now_ns / 1e9
    transport = t_s2 - t_s1
    assert t_s1 == pytest.approx(0.001)
    assert transport == pytest.approx(4.8, rel=0.10)
    assert transport == pytest.approx(0.239 / 0.050 + 0.050, abs=0.003)
    x_at_s2 = c.part_poses()["p1"][0]
    c.actuate("D1", False)  # the program resets D1 at S2↑
    run(c, t_s2 + 3.0, edges)
    x_rest, y_rest, angle = c.part_poses()["p1"]
    assert x_rest - x_at_s2 == pytest.approx(50.0 * 0.050, abs=0.1)  # stopping distance v·τ = 2.5 mm
    assert c.sensors["S2"] is True  # still inside the beam
    assert x_rest - 15.0 > 265.0 and x_rest + 15.0 < 300.0  # rests spanning ≈ 267–297 mm, 33 mm from the end
    assert y_rest == pytest.approx(50.0, abs=0.05) and abs(angle) < 1e-3
    assert ("S2", False) not in [(k, v) for k, v, _ in edges]
    assert "part fell off" not in [e.kind for e in c.events]


def test_conv3_transport_times():
    """All three belts running from t = 0; part centred on D1_OS. Spec §5.3: 4.9 s and 8.4 s (± 10 %)."""
    c = Conv3()
    for m in ("D1_VPRED", "D2_VPRED", "D3_VPRED"):
        c.actuate(m, True)
    c.place("D1_OS")
    edges = run(c, 14.0)
    d1, d2, d3 = rise(edges, "D1_OS"), rise(edges, "D2_OS"), rise(edges, "D3_OS")
    assert d1 == pytest.approx(0.001)
    assert d2 - d1 == pytest.approx(4.9, rel=0.10)
    assert d2 - d1 == pytest.approx((300.0 - 1.0 - 55.0) / 50.0 + 0.05, abs=0.01)
    assert d3 - d2 == pytest.approx(8.4, rel=0.10)
    assert d3 - d2 == pytest.approx((720.0 - 300.0) / 50.0, abs=0.005)  # crossing two dead plates costs < 5 ms


def test_conv3_stops_at_d3_os_and_waits_for_removal():
    c = Conv3()
    for m in ("D1_VPRED", "D2_VPRED", "D3_VPRED"):
        c.actuate(m, True)
    c.place("D1_OS")
    edges = []
    while not c.sensors["D3_OS"]:
        run(c, c.now_ns / 1e9 + 0.001, edges)
    c.actuate("D3_VPRED", False)
    run(c, c.now_ns / 1e9 + 2.0, edges)
    x = c.part_poses()["p1"][0]
    front = x + 15.0 - 510.0  # on D3: cut at 209 mm (beam edge) + 2.5 mm coasting; §5.3 says it spans ≈ 183–213
    assert front == pytest.approx(209.0 + 2.5, abs=0.3)
    assert c.sensors["D3_OS"] is True
    c.remove("D3_OS")
    assert c.sensors["D3_OS"] is False and c.parts == {}
    assert kinds(c)[-2:] == [("part removed", "D3_OS", "p1"), ("part left", "D3_OS", "p1")]


def test_conv2x2_transport_times():
    """Both belts running; part centred on D1_OS1. Spec §5.4: 4.2 s, 1.6 s, 4.5 s (± 10 %)."""
    c = Conv2x2()
    c.actuate("D1_VPRED", True)
    c.actuate("D2_VPRED", True)
    c.place("D1_OS1")
    edges = run(c, 11.0)
    a, b, d, e = (rise(edges, n) for n in ("D1_OS1", "D1_OS2", "D2_OS1", "D2_OS2"))
    assert b - a == pytest.approx(4.2, rel=0.10) and b - a == pytest.approx(4.23, abs=0.01)
    assert d - b == pytest.approx(1.6, rel=0.10) and d - b == pytest.approx(1.60, abs=0.005)
    assert e - d == pytest.approx(4.5, rel=0.10) and e - d == pytest.approx(4.50, abs=0.005)


# --- open end, end stop, jams, knocked off, several parts ----------------------------------------------------------


def test_part_falls_off_the_open_end():
    c = Conv1()
    c.place("S1")
    c.actuate("D1", True)
    run(c, 7.0)
    assert c.parts == {} and c.sensors == {"S1": False, "S2": False}
    fell = [e for e in c.events if e.kind == "part fell off"]
    assert len(fell) == 1 and fell[0].part == "p1" and fell[0].subject == "D1"
    # it tips over the end when its centre passes 330 mm (≈ 5.8 s) and is caught 25 mm below the belt
    assert 5.8 < fell[0].t_ns / 1e9 < 6.2 and fell[0].data["x"] > 330.0


def test_part_stays_against_the_end_stop():
    c = Conv1(end="stop")
    c.place("S1")
    c.actuate("D1", True)
    run(c, 12.0)
    hits = [e for e in c.events if e.kind == "end stop hit"]
    assert len(hits) == 1 and hits[0].part == "p1" and hits[0].data["speed"] == pytest.approx(50.0, abs=0.5)
    assert hits[0].t_ns / 1e9 == pytest.approx(0.050 + (330.0 - 55.0) / 50.0, abs=0.01)
    x = c.part_poses()["p1"][0]
    assert x == pytest.approx(315.0, abs=0.1)  # front face on the stop at 330 mm while the belt slips under it
    assert "part fell off" not in [e.kind for e in c.events]


def test_parts_pile_up_against_the_end_stop():
    c = Conv1(end="stop")
    for k in range(3):
        c.place("belt", offset_mm=20.0 + 50.0 * k)
    c.actuate("D1", True)
    run(c, 8.0)
    xs = sorted(p[0] for p in c.part_poses().values())
    assert xs == pytest.approx([255.0, 285.0, 315.0], abs=0.3)
    assert [e.part for e in c.events if e.kind == "end stop hit"] == ["p3"]


def test_held_part_never_reaches_s2():
    c = Conv1()
    c.place("S1")
    c.actuate("D1", True)
    run(c, 1.0)
    c.hold("p1")  # jam: the belt slips under it
    x_held = c.part_poses()["p1"][0]
    edges = run(c, 11.0)
    assert c.part_poses()["p1"][0] == pytest.approx(x_held, abs=0.01)
    assert ("S2", True) not in [(k, v) for k, v, _ in edges] and c.sensors["S2"] is False
    assert c.belt_speeds() == {"D1": 50.0}
    assert [k for k, _, _ in kinds(c)][-1] == "part jammed"


def test_release_lets_the_part_go_on():
    c = Conv1()
    c.place("S1")
    c.actuate("D1", True)
    run(c, 1.0)
    c.hold("belt")  # the front-most part on the belt
    run(c, 3.0)
    c.release("p1")
    edges = run(c, 12.0)
    x_held = 40.0 + 50.0 * (1.0 - 0.05)  # where the hold caught it (≈ 87.5 mm)
    assert rise(edges, "S2") == pytest.approx(3.0 + (294.0 - x_held - 15.0) / 50.0, abs=0.02)
    assert [k for k, _, _ in kinds(c)] == [
        "part placed",
        "part entered",
        "part left",
        "part jammed",
        "part released",
        "part entered",
        "part left",
        "part fell off",
    ]


def test_knocked_off_part_never_reaches_s2():
    c = Conv1()
    c.place("S1")
    c.actuate("D1", True)
    run(c, 0.2)
    assert c.sensors["S1"] is True
    c.knock_off("S1")
    assert c.sensors["S1"] is False  # it left the beam at once
    edges = run(c, 10.0)
    assert edges == [] and c.parts == {}
    ev = [(e.t_ns, e.kind, e.subject) for e in c.events]
    assert ev[2:] == [
        (200 * MS, "part knocked off", "D1"),
        (200 * MS, "part left", "S1"),
        (ev[4][0], "part fell off", "D1"),
    ]
    assert 200 * MS < ev[4][0] < 300 * MS  # it dropped 25 mm below the belt (≈ 71 ms of free fall)


def test_two_parts_20_mm_apart_give_two_s2_interruptions():
    c = Conv1()
    c.actuate("D1", True)
    c.place("S1")
    edges = run(c, 0.2)
    # wait until the first part's tail is 20 mm past the second's loading place: tail at 25 + 30 + 20 = 75 mm
    while c.part_poses()["p1"][0] - 15.0 < 40.0 + 15.0 + 20.0:
        run(c, c.now_ns / 1e9 + 0.001, edges)
    c.place("S1")
    run(c, 12.0, edges)
    s2 = [(v, t) for k, v, t in edges if k == "S2"]
    assert [v for v, _ in s2] == [True, False, True, False]
    gap_s = s2[2][1] - s2[1][1]
    assert gap_s == pytest.approx((20.0 - 2.0) / 50.0, abs=0.01)  # the 20 mm gap minus the 2 mm beam spot
    assert [e.part for e in c.events if e.kind == "part entered" and e.subject == "S2"] == ["p1", "p2"]


def test_station_occupied():
    c = Conv1()
    c.place("S1")
    with pytest.raises(StationOccupiedError, match="part p1 is there"):
        c.place("S1", offset_mm=10.0)
    assert list(c.parts) == ["p1"]
    c.place("S1", offset_mm=30.0)  # touching but not overlapping is fine
    with pytest.raises(ValueError, match="already in the plant"):
        c.place("S2", part="p1")
    with pytest.raises(KeyError, match="no station 'S9'"):
        c.place("S9")


# --- faults -----------------------------------------------------------------------------------------------------------


@pytest.mark.parametrize("dx", [-12.0, 8.0])
def test_shifted_sensor_moves_the_edge_by_dx_over_v(dx):
    def s2_rise(shift):
        c = Conv1()
        if shift:
            c.shift_sensor("S2", shift)
        c.place("S1")
        c.actuate("D1", True)
        return rise(run(c, 6.0), "S2")

    assert s2_rise(dx) - s2_rise(0.0) == pytest.approx(dx / 50.0, abs=0.0015)


def test_shifting_a_sensor_under_a_part_reports_only_the_difference():
    c = Conv1()
    c.place("S1")
    run(c, 0.01)
    c.shift_sensor("S1", 5.0)  # still under the part: no edge at all
    edges = run(c, 0.02)
    assert edges == [] and c.sensors["S1"] is True
    c.shift_sensor("S1", 40.0)  # now clear of it
    edges = run(c, 0.03)
    assert edges == [("S1", False, 0.021)]
    assert c.events[-1].kind == "part left" and c.events[-1].data == {"cause": "sensor shifted"}


def test_jammed_motor_moves_nothing():
    c = Conv1()
    c.place("S1")
    run(c, 0.1)
    x0 = c.part_poses()["p1"][0]
    c.jam_motor("D1", True)
    c.actuate("D1", True)
    edges = run(c, 5.0)
    assert c.part_poses()["p1"][0] == pytest.approx(x0, abs=1e-3)
    assert edges == [] and c.belt_speeds() == {"D1": 0.0}
    jam = [e for e in c.events if e.kind == "motor jammed"]
    assert [(e.t_ns, e.subject, e.data["commanded"]) for e in jam] == [(100 * MS, "D1", False)]
    c.jam_motor("D1", False)  # freed: the commanded belt starts
    edges = run(c, 10.0)
    assert rise(edges, "S2") == pytest.approx(5.0 + 0.05 + (294.0 - x0 - 15.0) / 50.0, abs=0.005)


def test_jam_while_running_stops_the_belt_within_tau():
    c = Conv1()
    c.place("S1")
    c.actuate("D1", True)
    run(c, 1.0)
    x0 = c.part_poses()["p1"][0]
    c.jam_motor("D1")
    run(c, 2.0)
    assert c.part_poses()["p1"][0] - x0 == pytest.approx(2.5, abs=0.1)


# --- time, reset, determinism -----------------------------------------------------------------------------------


def test_reset_restores_the_initial_state_and_keeps_the_live_dicts():
    c = Conv1(end="stop")
    sensors, events = c.sensors, c.events
    c.place("S1")
    c.actuate("D1", True)
    c.shift_sensor("S2", 30.0)
    c.jam_motor("D1")
    run(c, 1.0)
    c.reset(seed=7)
    assert c.sensors is sensors and c.events is events
    assert (c.now_ns, c.sensors, c.events, c.parts, c.belt_speeds()) == (
        0,
        {"S1": False, "S2": False},
        [],
        {},
        {"D1": 0.0},
    )
    assert c.barrier["S2"].x_actual == 295.0 and c.seed == 7
    assert c.place("S1") == "p1"


def test_a_long_step_is_split_and_keeps_the_clock():
    a, b = Conv1(), Conv1()
    for p in (a, b):
        p.place("S1")
        p.actuate("D1", True)
    for _ in range(200):
        a.step(25 * MS)  # a 25 ms scan: five 5 ms sub-steps
    for _ in range(1000):
        b.step(5 * MS)
    assert a.now_ns == b.now_ns == 5_000_000_000
    assert a.part_poses()["p1"] == b.part_poses()["p1"]


def test_idle_plant_skips_the_physics():
    c = Conv1()
    c.actuate("D1", True)
    for _ in range(100_000):  # 100 s of an empty running belt
        c.step(MS)
    assert c.now_ns == 100_000_000_000 and c.belt_speeds() == {"D1": 50.0} and c.events == []


SCRIPT = """
from plants import Conv3
MS = 1_000_000
c = Conv3()
for m in ("D1_VPRED", "D2_VPRED", "D3_VPRED"):
    c.actuate(m, True)
prev = dict(c.sensors)
edges = []
places = {0: (0.0, 0.0), 1500: (3.7, -4.2), 3200: (-2.9, 4.9)}
for k in range(16000):
    if k in places:
        c.place("D1_OS", offset_mm=places[k][0], angle_deg=places[k][1])
    if k == 9000:
        c.actuate("D2_VPRED", False)
    if k == 11000:
        c.actuate("D2_VPRED", True)
    c.step(MS)
    for n, v in c.sensors.items():
        if v != prev[n]:
            edges.append((n, v, c.now_ns))
            prev[n] = v
poses = [(p, x.hex(), y.hex(), a.hex()) for p, (x, y, a) in c.part_poses().items()]
events = [(e.t_ns, e.kind, e.subject, e.part) for e in c.events]
print(repr((edges, poses, events)))
"""


def _digest(text: str) -> str:
    return hashlib.sha256(text.strip().encode()).hexdigest()


def test_same_actions_give_identical_runs_here_and_in_a_subprocess():
    ns: dict = {}
    runs = []
    for _ in range(2):
        buf = io.StringIO()
        with contextlib.redirect_stdout(buf):
            exec(compile(SCRIPT, "<determinism>", "exec"), ns)
        runs.append(buf.getvalue())
    edges, poses, events = ast.literal_eval(runs[0])
    assert len(edges) >= 12 and len(poses) == 3 and len(events) > 10
    assert runs[0] == runs[1]
    out = subprocess.run(
        [sys.executable, "-c", SCRIPT],
        cwd=ROOT,
        capture_output=True,
        text=True,
        check=True,
        env={"PYTHONHASHSEED": "123", "PATH": "", "PYTHONPATH": str(ROOT), **WINDOWS_ROOT},
    )
    assert _digest(out.stdout) == _digest(runs[0])
