"""HBW, the stacker crane of 4.3.18: the rig on the plant protocol, its axes' speeds, cams and stopping distances
(spec §5.9), end stops, and the rack: put down, picked up, fallen, collided."""

from __future__ import annotations

import tomllib
from pathlib import Path

import pytest

from plants.hbw import HBW, X_CAMS, Y_CAMS, Z_CAMS
from plcsim.plant.check import check_plant
from plcsim.plant.protocol import Plant

ROOT = Path(__file__).resolve().parents[2]
MS = 1_000_000


def run_until(h: HBW, sensor: str, value: bool = True, limit_s: float = 30.0) -> float:
    while h.sensors[sensor] != value:
        h.step(MS)
        assert h.now_ns < limit_s * 1e9, f"{sensor} never became {value}"
    return h.now_ns / 1e9


def settle(h: HBW, ms: int = 500) -> None:
    for _ in range(ms):
        h.step(MS)


def drive(h: HBW, output: str, to: str) -> float:
    """Drive ``output`` until the cam ``to`` is reached, switch it off at once (a 1 ms scan) and let it coast."""
    h.actuate(output, True)
    t = run_until(h, to)
    h.actuate(output, False)
    settle(h)
    return t


def test_the_crane_keeps_the_protocol_and_is_registered_as_a_rig():
    h = HBW()
    assert isinstance(h, Plant)
    assert check_plant(h)["signals"] == 18
    rigs = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))["project"]["entry-points"][
        "plcsim.rigs"
    ]
    assert rigs["HBW"] == "plants.hbw:HBW"
    assert list(h.signals)[:12] == [*X_CAMS, *Y_CAMS, *Z_CAMS]  # Fig. 4.161: %I0.0 x1 … %I1.3 z3


def test_travel_times_match_the_speeds_of_section_5_9():
    h = HBW()
    assert round(drive(h, "x_vpravo", "x3"), 2) == 2.36  # 100 -> 334 mm (x3's zone) at 100 mm/s + τ = 20 ms
    t0 = h.now_ns / 1e9
    assert round(drive(h, "y_hore", "y6") - t0, 2) == 3.62  # 50 -> 266 mm at 60 mm/s + τ
    t0 = h.now_ns / 1e9
    assert round(drive(h, "z_vpred", "z3") - t0, 2) == 0.97  # 0 -> 76 mm at 80 mm/s + τ


@pytest.mark.parametrize(
    ("output", "cam", "axis", "zone"),
    [("x_vpravo", "x2", "x", 6.0), ("y_hore", "y2", "y", 4.0), ("z_vpred", "z3", "z", 4.0)],
)
def test_an_axis_switched_off_in_the_scan_that_sees_its_cam_stops_inside_the_zone(output, cam, axis, zone):
    h = HBW()
    drive(h, output, cam)
    a = getattr(h, axis)
    centre = {**X_CAMS, **Y_CAMS, **Z_CAMS}[cam]
    coast = a.s - (centre - zone)  # how far past the zone's edge it stopped: speed × τ
    assert coast == pytest.approx(a.speed * 0.02, abs=0.05)
    assert h.sensors[cam] and a.v == 0.0 and h.quiescent()


def test_a_drive_switched_off_too_late_overshoots_the_cam():
    """The zone is 12 mm: at 100 mm/s X crosses it in 0.12 s; switched off 0.25 s after the cam, it is past it."""
    h = HBW()
    h.actuate("x_vpravo", True)
    run_until(h, "x2")
    settle(h, 250)
    h.actuate("x_vlavo", False)
    h.actuate("x_vpravo", False)
    settle(h)
    assert not h.sensors["x2"] and h.x.s > X_CAMS["x2"] + 6.0


def test_an_axis_driven_past_its_last_cam_stalls_at_the_end_stop():
    h = HBW()
    h.actuate("x_vlavo", True)
    settle(h, 2000)
    assert h.x.s == 40.0 and h.x.stalled
    assert [(e.kind, e.subject, e.data["end"]) for e in h.events] == [("axis stalled", "X", "lo")]


def put_in(h: HBW, y_above: str, y_below: str) -> None:
    drive(h, "y_hore" if h.y.s < Y_CAMS[y_above] else "y_dole", y_above)
    drive(h, "z_vpred", "z3")
    drive(h, "y_dole", y_below)
    drive(h, "z_vzad", "z2")


def test_a_part_put_in_sits_on_its_place_and_is_taken_out_again():
    h = HBW()
    h.place("fork", part="p1")
    drive(h, "x_vpravo", "x2")
    put_in(h, "y4", "y3")  # put in at [2,2]: above the shelf to y4, in, down to y3, out
    assert h.rack.stored == {(2, 2): "p1"} and h.rack.on_fork is None
    drive(h, "z_vpred", "z3")  # take out: in under it at y3, up to y4, out
    drive(h, "y_hore", "y4")
    drive(h, "z_vzad", "z2")
    assert h.rack.stored == {} and h.rack.on_fork == "p1"
    kinds = [(e.kind, e.subject) for e in h.events]
    assert kinds == [("part placed", "fork"), ("part put down", "R22"), ("part picked up", "R22")]


def test_a_part_set_down_with_the_fork_not_far_enough_in_falls():
    h = HBW()
    h.place("fork", part="p1")
    drive(h, "y_hore", "y2")
    h.actuate("z_vpred", True)
    while h.z.s < 45.0:  # the part's centre only 5 mm over the shelf
        h.step(MS)
    h.actuate("z_vpred", False)
    settle(h)
    drive(h, "y_dole", "y1")
    assert h.rack.stored == {} and h.rack.on_fork is None
    assert [(e.kind, e.subject) for e in h.events][-1] == ("part fell off", "R11")


def test_the_fork_going_into_an_occupied_place_collides_and_never_puts_a_second_part_there():
    h = HBW()
    h.place("R11", part="a")
    h.place("fork", part="p1")
    drive(h, "y_hore", "y2")
    drive(h, "z_vpred", "z3")
    whats = [e.data["what"] for e in h.events if e.kind == "collision"]
    assert "the part on the fork hit the part on R11" in whats
    drive(h, "y_dole", "y1")
    assert h.rack.stored == {(1, 1): "a"}  # the carried one fell: two parts never share a place


def test_x_moving_with_the_fork_in_the_rack_hits_a_post():
    h = HBW()
    drive(h, "z_vpred", "z3")
    drive(h, "x_vpravo", "x2")
    assert [e.data["what"] for e in h.events if e.kind == "collision"] == ["the fork hit a post of the rack"]


def test_start_at_puts_an_axis_anywhere_before_the_run_and_draws_a_seeded_pose():
    h = HBW(seed=3)
    h.start_at("X", 160.0)
    assert not any(h.sensors[c] for c in X_CAMS)
    h.start_at("Y", (100.0, 140.0))
    first = h.y.s
    h.reset(seed=3)
    h.start_at("Y", (100.0, 140.0))
    assert h.y.s == first and 100.0 <= first <= 140.0
    with pytest.raises(ValueError, match="outside the axis's travel"):
        h.start_at("Z", 200.0)


def test_a_part_cannot_be_put_on_the_fork_in_the_rack_nor_on_a_full_place():
    h = HBW()
    h.place("R33", part="a")
    with pytest.raises(ValueError, match="already holds a"):
        h.place("R33", part="b")
    drive(h, "z_vpred", "z3")
    with pytest.raises(ValueError, match="in the rack"):
        h.place("fork", part="c")
