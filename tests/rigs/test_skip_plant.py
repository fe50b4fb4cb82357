"""SKIP, the skip hoist of 4.3.16: the protocol, the travel times of variant A of spec §5.7 against the textbook's
32 s, the converter's faults, the end buffers, the pour into the mixer and the rig's verbs."""

from __future__ import annotations

import tomllib
from pathlib import Path

import pytest

from plants.skip import Skip
from plcsim.plant.check import check_plant
from plcsim.plant.protocol import Plant

ROOT = Path(__file__).resolve().parents[2]
MS = 1_000_000
UP, DOWN, FAST, SLOW = "START_HORE", "START_DOLE", "RYCHLOST_RYCHLO", "RYCHLOST_POMALY"


def drive(p: Skip, **outputs: bool) -> None:
    for name, value in outputs.items():
        p.actuate(name, value)


def run_until(p: Skip, sensor: str, limit_s: float = 120.0) -> float:
    while not p.sensors[sensor]:
        p.step(MS)
        assert p.now_ns < limit_s * 1e9, f"{sensor} never reached"
    return p.now_ns / 1e9


def run(p: Skip, seconds: float) -> None:
    for _ in range(round(seconds * 1000)):
        p.step(MS)


def events(p: Skip, kind: str) -> list:
    return [e for e in p.events if e.kind == kind]


def auto_ascent(p: Skip) -> tuple[float, float]:
    """The reference program's ascent: fast from the bottom, slow from SPOMAL, stop at HORNY."""
    drive(p, START_HORE=True, RYCHLOST_RYCHLO=True)
    t_slow = run_until(p, "SNIMAC_SPOMAL")
    drive(p, RYCHLOST_RYCHLO=False, RYCHLOST_POMALY=True)
    t_top = run_until(p, "SNIMAC_HORNY")
    drive(p, START_HORE=False, RYCHLOST_POMALY=False)
    return t_slow, t_top


def test_the_skip_keeps_the_protocol_and_is_registered_as_a_rig():
    plant = Skip()
    assert isinstance(plant, Plant)
    assert check_plant(plant)["signals"] == 7
    rigs = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))["project"]["entry-points"][
        "plcsim.rigs"
    ]
    assert rigs["SKIP"] == "plants.skip:Skip"
    assert list(plant.signals)[:3] == ["SNIMAC_DOLNY", "SNIMAC_HORNY", "SNIMAC_SPOMAL"]  # %I0.0..%I0.2, Fig. 4.132


def test_a_full_skip_climbs_inside_the_textbook_s_32_s_with_a_small_reserve():
    p = Skip()
    p.fill("skip")
    assert p.sensors == {"SNIMAC_DOLNY": True, "SNIMAC_HORNY": False, "SNIMAC_SPOMAL": False}
    t_slow, t_top = auto_ascent(p)
    assert round(t_slow, 1) == 20.4 and round(t_top, 1) == 28.6
    assert 28.6 < 32.0 < 28.6 * 1.15  # "a small reserve": 32 s is 12 % above the travel
    top = events(p, "speed measured")[-1]
    assert top.subject == "SNIMAC_HORNY" and 24.0 < top.data["speed_mm_s"] <= 25.0 * 1.05
    assert events(p, "speed measured")[0].data["speed_mm_s"] == pytest.approx(40.0 * 0.97, abs=0.01)  # 3 % slip
    run(p, 1.0)
    assert p.quiescent() is False  # it pours
    assert 990.0 < p.winch.s < 993.0 and p.sensors["SNIMAC_HORNY"]


def test_the_empty_skip_descends_slowly_inside_45_s_and_a_manual_ascent_outlasts_32_s():
    p = Skip()
    p.fill("skip")
    auto_ascent(p)
    run(p, 6.0)
    assert p.bucket.load_g == 0.0
    t0 = p.now_ns / 1e9
    drive(p, START_DOLE=True, RYCHLOST_POMALY=True)
    t = run_until(p, "SNIMAC_DOLNY") - t0
    assert round(t, 1) == 39.4 and 32.0 < t < 45.0 < t * 1.15
    drive(p, START_DOLE=False, RYCHLOST_POMALY=False)
    run(p, 0.5)
    assert p.quiescent() and 8.0 < p.winch.s < 10.0
    p.fill("skip")
    t0 = p.now_ns / 1e9
    drive(p, START_HORE=True, RYCHLOST_POMALY=True)
    assert round(run_until(p, "SNIMAC_HORNY") - t0, 1) == 40.6  # > 32 s: the up alarm's trap in manual mode


def test_the_batch_pours_into_the_mixer_during_the_dwell_and_a_short_dwell_leaves_some_behind():
    full, short = Skip(), Skip()
    for p, dwell in ((full, 6.0), (short, 0.5)):
        p.fill("skip")
        auto_ascent(p)
        run(p, dwell)
        drive(p, START_DOLE=True, RYCHLOST_POMALY=True)
        run(p, 2.0)
    (done,) = events(full, "pour ended")
    assert done.subject == "mixer" and done.data["fraction"] == 1.0 and full.bucket.bin_g == pytest.approx(200.0)
    assert done.t_ns - events(full, "speed measured")[-1].t_ns < 2.5e9  # ≈ 3 s of pouring, most of it at the top
    (cut,) = events(short, "pour ended")
    assert 0.2 < cut.data["fraction"] < 0.6 and cut.data["left_g"] > 80.0
    assert short.bucket.load_g == pytest.approx(cut.data["left_g"], abs=1e-3)  # the rest rides down again


def test_the_converter_trips_on_both_directions_and_holds_the_brake_without_a_speed():
    p = Skip()
    drive(p, START_HORE=True, START_DOLE=True, RYCHLOST_RYCHLO=True)
    run(p, 1.0)
    assert p.winch.s == 8.5 and [e.subject for e in events(p, "converter fault")] == ["VFD"]
    drive(p, START_DOLE=False)
    run(p, 1.0)
    assert p.winch.s > 20.0  # the fault clears when the commands agree again
    drive(p, RYCHLOST_RYCHLO=False)
    run(p, 1.0)
    s = p.winch.s
    run(p, 1.0)
    assert p.winch.s == s and p.quiescent() and len(events(p, "converter warning")) == 1
    drive(p, RYCHLOST_RYCHLO=True, RYCHLOST_POMALY=True)  # both speed bits: fast
    run(p, 2.0)
    assert p.winch.v == pytest.approx(40.0)


def test_a_dead_slow_down_sensor_means_a_fast_arrival_and_the_skip_runs_into_the_top_buffer_if_not_stopped():
    p = Skip()
    drive(p, START_HORE=True, RYCHLOST_RYCHLO=True)
    run_until(p, "SNIMAC_HORNY")
    assert events(p, "speed measured")[-1].data["speed_mm_s"] == pytest.approx(40.0)  # overspeed at the top
    run(p, 2.0)
    (hit,) = events(p, "end stop hit")
    assert hit.subject == "top buffer" and hit.data["speed_mm_s"] == pytest.approx(40.0)
    assert p.winch.s == 1030.0 and not p.sensors["SNIMAC_HORNY"]  # past the cam, against the buffer
    drive(p, START_HORE=False, START_DOLE=True, RYCHLOST_RYCHLO=False, RYCHLOST_POMALY=True)
    run(p, 2.0)
    assert p.winch.s < 1000.0 and len(events(p, "end stop hit")) == 1


def test_a_jammed_rope_stops_the_skip_until_it_is_freed():
    p = Skip()
    drive(p, START_HORE=True, RYCHLOST_POMALY=True)
    run(p, 2.0)
    p.jam_motor("START_HORE", True)
    s = p.winch.s
    run(p, 3.0)
    assert p.winch.s == s and events(p, "motor jammed")[0].subject == "skip"
    p.jam_motor("skip", False)
    run(p, 1.0)
    assert p.winch.s > s + 20.0
    with pytest.raises(KeyError, match="no drive"):
        p.jam_motor("SNIMAC_DOLNY", True)


def test_the_hopper_fills_only_at_the_bottom_and_the_mixer_discharges():
    p = Skip()
    drive(p, START_HORE=True, RYCHLOST_RYCHLO=True)
    run(p, 2.0)
    with pytest.raises(ValueError, match="not under the dosing hopper"):
        p.fill("skip")
    p.bucket.bin_g = 150.0
    p.discharge("mixer")
    assert p.bucket.bin_g == 0.0 and events(p, "mixer discharged")[0].data["mass_g"] == 150.0


def test_a_shifted_sensor_reads_at_its_new_place_at_once():
    p = Skip()
    p.shift_sensor("SNIMAC_DOLNY", 30.0)
    p.step(MS)
    assert p.sensors["SNIMAC_DOLNY"] is False
    p.shift_sensor("SNIMAC_DOLNY", 0.0)
    p.step(MS)
    assert p.sensors["SNIMAC_DOLNY"] is True


def test_the_drawing_shows_the_tipped_bucket_and_the_pouring_stream():
    p = Skip()
    p.fill("skip")
    auto_ascent(p)
    run(p, 0.5)
    paths = {d.path for d in p.dynamic_drawables()}
    assert {"skip/bucket", "skip/load", "mixer/load", "skip/pour/0", "VFD/state"} <= paths
    static = {d.text for d in p.static_drawables() if d.kind == "label"}
    assert {"SNIMAC_DOLNY", "SNIMAC_SPOMAL", "SNIMAC_HORNY", "mixer"} <= static
