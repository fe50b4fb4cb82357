"""SLIDE, the hydraulic feed slide of the Tecomat manual's EX-19: the rig on the plant protocol, its speeds and
limit switches, and the manual's program run on it as printed through the bare-rig wiring
(``plcsim run SLIDE --program examples/tecomat/ex19_feed_slide.il``)."""

from __future__ import annotations

import tomllib
from pathlib import Path

from plants.slide import Slide
from plcsim.apps.live.build import rig_simulation
from plcsim.frontends import read_program
from plcsim.plant.check import check_plant
from plcsim.plant.protocol import Plant
from plcsim.scenario.planning import Scenario
from plcsim.scenario.verbs import jam_motor, press

ROOT = Path(__file__).resolve().parents[2]
MS = 1_000_000


def test_the_slide_keeps_the_protocol_and_is_registered_as_a_rig():
    plant = Slide()
    assert isinstance(plant, Plant)
    assert check_plant(plant)["signals"] == 11
    rigs = tomllib.loads((ROOT / "pyproject.toml").read_text(encoding="utf-8"))["project"]["entry-points"][
        "plcsim.rigs"
    ]
    assert rigs["SLIDE"] == "plants.slide:Slide"


def test_the_signals_are_numbered_as_the_manual_s_addresses():
    sensors = [n for n, s in Slide().signals.items() if s.direction == "sensor"]
    actuators = [n for n, s in Slide().signals.items() if s.direction == "actuator"]
    assert sensors[:4] == ["start1", "start2", "k1", "k5"]  # X0.0..X0.3 as EX-19's #def
    assert actuators == ["em1", "em2", "em3"]  # Y0.0, Y0.1 as EX-19's #def, then EM3


def run_until(plant: Slide, sensor: str) -> float:
    while not plant.sensors[sensor]:
        plant.step(MS)
    return plant.now_ns / 1e9


def test_working_feed_rapid_traverse_cams_and_end_stops():
    s = Slide()
    s.actuate("em1", True)
    t = {k: run_until(s, k) for k in ("k2", "k3")}
    assert round(t["k3"] - t["k2"], 2) == 1.25  # 50 mm at the working feed, 40 mm/s
    s.actuate("em3", True)
    t["k4"] = run_until(s, "k4")
    assert round(t["k4"] - t["k3"], 2) == 0.45  # 50 mm at the rapid traverse, 120 mm/s, with the drive's lag
    run_until(s, "k5")
    for _ in range(500):
        s.step(MS)
    assert s.slide.s == 203.0 and s.slide.stalled and s.sensors["k5"] is False  # driven on past k5 into the stop
    assert [(e.kind, e.data["end"]) for e in s.events if e.kind == "axis stalled"] == [("axis stalled", "hi")]
    s.actuate("em2", True)
    assert [e.kind for e in s.events][-1] == "interlock violated"  # both valves open: the slide stops
    for _ in range(100):
        s.step(MS)
    assert s.slide.s == 203.0 and s.quiescent()


def test_the_manual_s_ex19_runs_on_the_rig_as_printed():
    program = read_program(ROOT / "examples" / "tecomat" / "ex19_feed_slide.il")
    scenario = Scenario(
        "one working cycle",
        *press("start1", t="1s", hold="300ms"),  # START1 alone: nothing
        *press("start1", t="2s", hold="300ms"),
        *press("start2", t="2.1s", hold="300ms"),  # both held together at k1: EM1
        duration="30s",
    )
    sim = rig_simulation(Slide(), program, scenario, cycle="10ms")
    sim.run()
    tr = sim.trace
    ms = {n: [(a // MS, b // MS if b else None) for a, b in tr.intervals(n)] for n in ("em1", "em2", "k1", "k5")}
    assert ms["em1"][0][0] == 2110  # the cycle that sees both buttons
    k5 = ms["k5"][0][0]
    assert 2110 + 4930 <= k5 <= 2110 + 4950  # 195.5 mm at 40 mm/s and the 50 ms lag, seen by a 10 ms cycle
    assert ms["em1"] == [(2110, k5 + 10)]  # EM1 reset in the cycle that sees K5 (outputs: at a cycle's end)
    assert ms["em2"][0][0] == k5 + 5010  # 5 s at K5 (TON, 1 s base): the cycle 5 s after K5's, written at its end
    back = ms["k1"][1][0]
    assert ms["em2"] == [(k5 + 5010, back + 10)]  # latched after leaving K5, reset at K1
    assert sim.plant.slide.s > 0.0 and sim.plant.sensors["k1"]  # at rest in the initial position again


def test_a_jammed_slide_stays_put():
    scenario = Scenario(
        "jammed",
        jam_motor("em1", t="500ms"),
        *press("start1", t="1s", hold="300ms"),
        *press("start2", t="1s", hold="300ms"),
        duration="5s",
    )
    sim = rig_simulation(Slide(), read_program(ROOT / "examples" / "tecomat" / "ex19_feed_slide.il"), scenario)
    sim.run()
    assert sim.trace.column("em1")[-1] and sim.plant.slide.s == 1.5 and sim.plant.sensors["k1"]
