"""PUNCH, the punching machine of 6.3 (plants/punch.py, plants/components/press.py): its figures against
spec/exercises.md §5.10, the press's stall and its effect on parts, the interlock events and the KS1/KS2 option."""

from __future__ import annotations

import numpy as np
import pytest

from plants import RIGS, Punch
from plants.components.component import Bench
from plants.components.press import Press
from plcsim import CPU, Tag
from plcsim.plant.check import check_plant
from plcsim.scenario.planning import Scenario
from plcsim.sim.simulation import Simulation
from plcsim.sim.wiring import Wire
from plcsim.trace.plot import default_signals, timing_diagram

MS = 1_000_000


def run_until(p: Punch, signal: str, value: bool = True, limit_s: float = 20.0) -> float:
    """Step 1 ms at a time until the sensor has the value; the time it took (s)."""
    t0 = p.now_ns
    while p.sensors[signal] != value:
        p.step(MS)
        assert p.now_ns - t0 < limit_s * 1e9, f"{signal} never became {value}"
    return (p.now_ns - t0) / 1e9


def kinds(p: Punch, kind: str) -> list:
    return [e for e in p.events if e.kind == kind]


def stroke(p: Punch) -> float:
    """One stroke as the textbook's program drives it: down to KS2, up to KS1; its duration (s)."""
    t0 = p.now_ns
    p.actuate("M2_DOLE", True)
    run_until(p, "KS2")
    p.actuate("M2_DOLE", False)
    p.actuate("M2_HORE", True)
    run_until(p, "KS1")
    p.actuate("M2_HORE", False)
    return (p.now_ns - t0) / 1e9


def test_the_rig_is_registered_and_keeps_the_protocol():
    p = RIGS["PUNCH"]()
    assert list(p.signals) == ["OS1", "OS2", "M1_VPRED", "M1_VZAD", "M2_DOLE", "M2_HORE", "KS1", "KS2"]
    assert check_plant(p)["signals"] == 8
    assert p.sensors == {"OS1": False, "OS2": False, "KS1": True, "KS2": False}  # the press waits at the top


def test_nominal_times_match_the_proposal():
    """§5.10: OS1 -> OS2 forward ≈ 4.3 s, OS2 -> OS1 back ≈ 3.9 s, one stroke ≈ 2.7 s."""
    p = Punch()
    pid = p.place("OS1")
    p.step(MS)
    p.actuate("M1_VPRED", True)
    forward = run_until(p, "OS2")
    p.actuate("M1_VPRED", False)
    p.actuate("M1_VZAD", True)
    back = run_until(p, "OS1")
    p.actuate("M1_VZAD", False)
    for _ in range(300):
        p.step(MS)
    x = p.parts[pid].x
    assert forward == pytest.approx(4.28, abs=0.01)
    assert back == pytest.approx(3.93, abs=0.01)
    assert 43.0 < x - 15.0 < 45.0  # stopped by its leading face: it spans ≈ 44-74 mm, inside the OS1 beam
    assert stroke(p) == pytest.approx(2.72, abs=0.01)
    assert kinds(p, "interlock violated") == [] and kinds(p, "part fell off") == []


def test_a_stroke_on_a_part_under_the_press_is_counted_with_its_offset():
    p = Punch()
    pid = p.place("OS2", offset_mm=-3.0)
    run_until(p, "OS2")
    assert stroke(p) == pytest.approx(2.72, abs=0.01)
    (e,) = kinds(p, "press stroke")
    assert e.part == pid and e.subject == "M2" and e.data["offset_mm"] == pytest.approx(2.0, abs=0.05)
    assert kinds(p, "part damaged") == [] and kinds(p, "axis stalled") == []


def test_a_press_driven_past_its_switch_stalls_and_says_so():
    p = Punch()
    p.actuate("M2_HORE", True)  # already at KS1: up into the upper end stop
    for _ in range(300):
        p.step(MS)
    (e,) = kinds(p, "axis stalled")
    assert e.subject == "M2" and e.data["end"] == "lo"  # the travel's start: the upper end stop
    assert p.press.z == 108.0 and p.sensors["KS1"]  # the cam keeps the switch pressed in overtravel
    assert p.press.axis.stalled and p.press.axis.s == 0.0
    p.actuate("M2_HORE", False)
    p.actuate("M2_DOLE", True)  # down past KS2 with nothing under it
    for _ in range(2000):
        p.step(MS)
    assert [e.data["end"] for e in kinds(p, "axis stalled")] == ["lo", "hi"]
    assert p.press.z == 69.0 and p.sensors["KS2"] and not p.sensors["KS1"]


def test_a_ram_driven_into_a_part_stalls_on_it_and_damages_it():
    p = Punch()
    pid = p.place("OS2", offset_mm=0.0)
    p.actuate("M2_DOLE", True)
    for _ in range(2000):
        p.step(MS)
    (stall,) = kinds(p, "axis stalled")
    assert stall.data["end"] == "hi" and stall.data["position"] == pytest.approx(38.0, abs=0.05)  # tip at 70 mm
    (damage,) = kinds(p, "part damaged")
    assert damage.part == pid and "driven into it" in damage.data["cause"]
    assert p.press.z == pytest.approx(70.0, abs=0.05)


def test_a_belt_moving_a_part_under_the_lowered_tool_damages_it():
    """6.3.4 without KS1: the belt reverses while the tool is still at the part."""
    p = Punch()
    pid = p.place("OS2")
    p.actuate("M2_DOLE", True)
    run_until(p, "KS2")
    p.actuate("M2_DOLE", False)
    p.actuate("M2_HORE", True)
    p.actuate("M1_VZAD", True)
    run_until(p, "KS1")
    (damage,) = kinds(p, "part damaged")
    assert damage.part == pid and "under the lowered tool" in damage.data["cause"]
    reasons = [(e.subject, e.data["reason"]) for e in kinds(p, "interlock violated")]
    assert reasons == [
        ("M1", "belt driven while the press is away from the top"),
        ("M2", "press driven while the belt is driven"),
    ]


def test_interlocks_do_not_depend_on_the_order_of_one_scans_outputs():
    """R M1_VZAD and S M1_VPRED in one scan reach the plant one after the other; no violation either way."""
    for order in ((("M1_VPRED", True), ("M1_VZAD", False)), (("M1_VZAD", False), ("M1_VPRED", True))):
        p = Punch()
        p.actuate("M1_VZAD", True)
        p.step(MS)
        for name, value in order:
            p.actuate(name, value)
        p.step(MS)
        assert kinds(p, "interlock violated") == []
        assert p.belt.target == 40.0


def test_both_directions_stop_the_motor_and_are_logged_once():
    p = Punch()
    for name in ("M1_VPRED", "M1_VZAD", "M2_DOLE", "M2_HORE"):
        p.actuate(name, True)
    for _ in range(50):
        p.step(MS)
    reasons = sorted((e.subject, e.data["reason"]) for e in kinds(p, "interlock violated"))
    assert reasons == [
        ("M1", "both directions commanded"),
        ("M2", "both directions commanded"),
        ("M2", "press driven while the belt is driven"),
    ]
    assert p.belt.target == 0.0 and p.press.axis.direction == 0 and p.press.z == 105.5


def test_a_jammed_press_stops_where_it_is():
    p = Punch()
    p.actuate("M2_DOLE", True)
    for _ in range(500):
        p.step(MS)
    p.jam_motor("M2_DOLE")
    z = p.press.z
    for _ in range(3000):
        p.step(MS)
    assert p.press.z == z and 92.5 < z < 93.5 and not p.sensors["KS2"] and not p.sensors["KS1"]
    assert [e.kind for e in p.events] == ["motor jammed"]  # the fault's own report; a stall is a program's doing
    assert p.events[0].data["commanded"]
    p.jam_motor("M2_DOLE", False)
    run_until(p, "KS2")
    assert [e.kind for e in p.events][-1] == "press stroke"


def test_ks1_lower_swaps_the_switch_names():
    """The model text's reading (KS1 lower, KS2 upper): at rest KS2 is actuated."""
    p = Punch(ks1="lower")
    assert p.sensors["KS2"] and not p.sensors["KS1"]
    p.actuate("M2_DOLE", True)
    run_until(p, "KS1")
    assert p.press.z < 72.0
    with pytest.raises(ValueError, match="ks1 must be 'upper' or 'lower'"):
        Punch(ks1="top")


def test_a_part_carried_back_past_os1_falls_off_the_loading_end():
    p = Punch()
    pid = p.place("OS1")
    p.actuate("M1_VZAD", True)
    for _ in range(3000):
        p.step(MS)
    (e,) = kinds(p, "part fell off")
    assert e.part == pid and pid not in p.parts


def test_the_press_rejects_an_impossible_geometry():
    with pytest.raises(ValueError, match="bottom < stroke_depth < rearm < top"):
        Press(parts_under=lambda lo, hi: (), top=70.0)


def test_the_press_turns_cleanly_whatever_the_order_of_its_relays():
    """6.3.5 at KS1: S M2_DOLE and R M2_HORE in one scan; the relays arrive one after the other."""
    for order in ((("M2_DOLE", True), ("M2_HORE", False)), (("M2_HORE", False), ("M2_DOLE", True))):
        host = Bench()
        press = Press(parts_under=lambda lo, hi: ())
        press.reset(host)
        press.actuate(host, "M2_HORE", True)
        host.step(press)
        for name, value in order:
            press.actuate(host, name, value)
        host.step(press)
        assert host.events == [] and press.axis.direction == 1  # down (the travel runs downward)


def test_same_seed_same_run():
    def run() -> tuple:
        p = Punch(seed=3)
        p.place("OS2", offset_mm=1.3, angle_deg=2.0)
        stroke(p)
        return tuple((e.t_ns, e.kind, e.part) for e in p.events), p.press.z

    assert run() == run()


def one_stroke_run() -> Simulation:
    """A program that drives the press down to KS2 and back up to KS1, once."""
    tags = {n: Tag(a) for n, a in (("KS1", "%I0.2"), ("KS2", "%I0.3"), ("M2_DOLE", "%Q0.2"), ("M2_HORE", "%Q0.3"))}
    tags["DONE"] = Tag("%M0.0")
    program = (
        "def OB1(t):\n"
        "    if t.KS2:\n        t.DONE = True\n"
        "    t.M2_DOLE = not t.DONE and not t.KS2\n"
        "    t.M2_HORE = t.DONE and not t.KS1\n"
    )
    wires = [Wire(n, n) for n in ("KS1", "KS2", "M2_DOLE", "M2_HORE")]
    sim = Simulation(CPU(tags, program), Punch(), wires, Scenario("stroke", duration="4s"))
    sim.run()
    return sim


def test_the_ram_height_is_traced_as_an_analog_value_and_drawn_as_a_line():
    """The tool tip height is a trace column of kind analog (the plant's TRACED_OBSERVABLES), sampled with the
    inputs of each scan: 105.5 mm at rest, down at 25 mm/s to the KS2 make point (72 mm) and back."""
    tr = one_stroke_run().trace
    z = tr.column("plant:M2.z")
    assert (tr.kinds["plant:M2.z"], tr.types["plant:M2.z"]) == ("analog", "real")
    assert z[0] == 105.5 and z[-1] == pytest.approx(105.5, abs=0.05)  # stopped at KS1: it coasts ≈ 0.5 mm
    made = int(np.argmax(tr.column("KS2")))  # the first scan that reads KS2
    assert z[made] == pytest.approx(72.0, abs=0.03) and tr.times[made] / 1e9 == pytest.approx(1.361, abs=0.002)
    assert 71.5 < z.min() < 72.0  # reversed at KS2 the ram turns within τ 20 ms (a stop there coasts to 71.5 mm)
    assert np.diff(z[300:1000]) == pytest.approx(-0.025, abs=1e-6)  # at 25 mm/s (after 15 τ): 0.025 mm per scan
    fig = timing_diagram(tr, ["KS1", "KS2", "plant:M2.z"])
    (lane,) = [ln for ln in fig.axes[0].lines if ln.get_gid() == "lane:plant:M2.z"]
    assert lane.get_drawstyle() == "default" and len(lane.get_xdata()) > 2000  # a line through the samples
    assert "plant:M2.z" in default_signals(tr)


def test_a_trace_of_no_signals_still_records_the_plants_measurements():
    """``signals=[]`` keeps only the analog observables: the row is the sample alone (it was a syntax error)."""
    tags = {"M2_DOLE": Tag("%Q0.2")}
    cpu = CPU(tags, "def OB1(t):\n    t.M2_DOLE = True\n")
    sim = Simulation(cpu, Punch(), [Wire("M2_DOLE", "M2_DOLE")], signals=[])
    sim.run("200ms")
    z = sim.trace.column("plant:M2.z")
    assert len(z) == 200 and z[0] == 105.5 and z[-1] < 105.5  # the ram is going down


def test_a_plant_whose_traced_observables_disagree_is_refused():
    class Wrong(Punch):
        def sample_observables(self) -> tuple[float, ...]:
            return (0.0,)

    with pytest.raises(AssertionError, match=r"sample_observables\(\) != observables\(\)"):
        check_plant(Wrong())
    assert check_plant(Punch())["signals"] == 8
