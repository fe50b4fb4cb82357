"""4.3.18, the stacker crane, beyond its shipped solutions (``test_exercises.py`` grades those): the operator's
requests, and the hard question of next-phase §a.4 — a cam zone against the stopping distance. At the course's
1 ms scan the reference stops inside every zone; a slow scan lets the axes overshoot, and then the grade shows it
(the estimates drift, the axes hunt and run into their end stops), rather than a crane that stops by magic."""

from __future__ import annotations

from itertools import pairwise

from exercises._hbw import operator, random_requests
from exercises.ex_4_3_18 import EXERCISE, FAILED, SHIFTED
from plcsim.check import Context
from plcsim.frontends import read_program
from plcsim.scenario.verbs import TimeSpec

REFERENCE = read_program(EXERCISE.reference.path)


def run(scenario: str, **cpu):
    sim = EXERCISE.simulation(REFERENCE, scenario, seed=1, **cpu)
    sim.run()
    ctx = Context.of(sim.trace)
    failed = {gc.name: gc.check.evaluate(ctx).message for gc in EXERCISE.checks_for(scenario)}
    return sim.trace, {name: msg for name, msg in failed.items() if not _passed(ctx, name)}


def _passed(ctx: Context, name: str) -> bool:
    return next(gc for gc in EXERCISE.checks if gc.name == name).check.evaluate(ctx).passed


def test_the_operator_s_steps_of_a_request_come_in_their_order_whatever_is_drawn():
    actions = operator([("take", 1, 1), ("put", 2, 2)], stocked={"R11": "a"})
    second = [a for a in actions if a.when is not None]  # the second request: after the first part was lifted
    assert [a.verb for a in second] == ["remove", "place", "write", "write", "write"]
    windows = sorted({(a.delay.lo_ns, a.delay.hi_ns) for a in second})  # DATA.x and DATA.y share one
    assert all(a[1] < b[0] for a, b in pairwise(windows)), windows
    assert TimeSpec.parse("2s..2.2s") == second[0].delay  # the program's 2 s to finish a request
    assert second[-1].target == "DATA.Poziadavka_naloz" and second[-1].args["value"] is True


def test_seeded_requests_put_only_into_free_places_and_take_only_from_full_ones():
    for seed in range(20):
        full = {(2, 2)}
        for kind, x, y in random_requests(seed, 6, {(2, 2)}):
            assert ((x, y) in full) == (kind == "take")
            (full.discard if kind == "take" else full.add)((x, y))


def test_a_slow_scan_overshoots_the_cams_and_the_grade_shows_it():
    """150 ms scans: X travels 15 mm per scan across a 12 mm cam, Z 12 mm across an 8 mm one. The axes run out of
    their zones, the textbook's ±0.5 on the N edge sends them back, they hunt; where a scan misses a cam altogether
    the estimate drifts from the true position and an axis runs into its end stop."""
    trace, failed = run(SHIFTED, cycle="150ms")
    assert len(trace.rises("x_vlavo")) >= 3 and len(trace.rises("x_vpravo")) >= 3  # X hunts
    assert "no axis is driven against an end stop" in failed
    assert any(name.startswith("OS_") and "aktualna" in name for name in failed), failed


def test_at_a_1_ms_scan_every_axis_stops_inside_its_cam_and_never_hunts():
    trace, failed = run(SHIFTED)
    assert failed == {}
    assert len(trace.rises("x_vpravo")) == 1 and len(trace.rises("x_vlavo")) == 0


def test_a_failed_cam_makes_the_reference_hunt_between_x1_and_x3_without_harm():
    trace, failed = run(FAILED)
    assert failed == {}
    assert len(trace.rises("x3")) == 1 and len(trace.rises("x_vlavo")) == 1  # x2 never closes: X finds x3, turns
    assert not any(e.kind == "part put down" for e in trace.events)
    assert max(trace.column("plant:Z.s")) < 5.0  # the fork never goes into the rack
