"""The punching-machine exercises 6.3.1–6.3.5 beyond what tests/course/test_exercises.py and
tests/course/test_seeds.py grade: the KS1/KS2 plant option against the textbook's contradiction, determinism of a
PUNCH run, and the truth the checks read from the plant's events."""

from __future__ import annotations

import dataclasses
from itertools import pairwise

import pytest

from exercises import get
from exercises._punch import TAKEN_FROM_THE_PRESS, strokes_of, visits
from plants import Punch
from plcsim.grading.grader import grade


def failed(report) -> set[str]:
    return {c.check for c in report.failed()}


def test_the_model_texts_ks1_lower_is_a_plant_option():
    """Text issue 12: the solutions' KS1 = upper runs on the default rig; on the rig wired as the model text reads
    (KS1 lower), the textbook's reference punches nothing and the program written for that reading does the job
    (the checks that name KS1 and KS2 are written for the default rig; the plant's own account is not)."""
    ex = get("6.3.3")
    literal = dataclasses.replace(ex, rig=lambda: Punch(ks1="lower"))
    text_reading = ex.solution("wrong-ks1-lower").path
    assert grade(ex, ex.reference.path, seed=2).passed
    assert not grade(ex, text_reading, seed=2).passed
    on_literal = grade(literal, ex.reference.path, seed=2, scenarios=["three objects"])
    assert "every object under the press is punched exactly once" in failed(on_literal)
    assert "the press is never driven against an end stop" in failed(on_literal)
    plants_word = {
        "every object under the press is punched exactly once",
        "every object gets exactly one stroke",
        "the press starts once per object, never without one",
        "the press is never driven against an end stop",
        "the machine reports no interlock violation",
        "no object is damaged by the press",
    }
    assert not failed(grade(literal, text_reading, seed=2)) & plants_word


def test_a_punch_run_is_the_same_bit_for_bit_with_the_same_seed():
    ex = get("6.3.5")

    def run(seed: int):
        sim = ex.simulation(ex.reference.program(), "two strokes, then one", seed=seed)
        sim.run()
        return sim.trace.table.tobytes(), [(e.t_ns, e.kind, e.subject, e.part) for e in sim.trace.events]

    first = run(4)
    assert run(4) == first
    assert run(5) != first  # the seed moves the operator's times and the parts' poses


def test_the_checks_see_each_stay_under_the_press_and_its_strokes():
    """6.3.5, two moves of three strokes: two stays in the OS2 beam, three strokes on the part in each, 2.72 s apart
    (down to KS2 and back at 25 mm/s)."""
    ex = get("6.3.5")
    sim = ex.simulation(ex.reference.program(), "two moves, three strokes", seed=1)
    sim.run()
    stays = visits(sim.trace)
    strokes = strokes_of(sim.trace)
    assert [p for p, _, _ in stays] == ["p1", "p1"]
    for _, t0, t1 in stays:
        mine = [t for t, p in strokes if p == "p1" and t0 <= t <= t1]
        assert len(mine) == 3
        assert [round((b - a) / 1e9, 2) for a, b in pairwise(mine)] == [2.72, 2.72]
    assert len(strokes) == 6 and all(p == "p1" for _, p in strokes)


@pytest.mark.parametrize("number", ["6.3.1", "6.3.2", "6.3.3", "6.3.4", "6.3.5"])
def test_every_task_wires_the_whole_model(number):
    """All eight signals of Fig. 6.24 at the textbook's addresses, OS1/OS2 NC, KS1/KS2 NO."""
    ex = get(number)
    rows = {r.tag: (r.address, r.wiring) for r in ex.io if r.direction in ("input", "output")}
    assert rows == {
        "OS1": ("%I0.0", "NC"),
        "OS2": ("%I0.1", "NC"),
        "KS1": ("%I0.2", "NO"),
        "KS2": ("%I0.3", "NO"),
        "M1_VPRED": ("%Q0.0", None),
        "M1_VZAD": ("%Q0.1", None),
        "M2_DOLE": ("%Q0.2", None),
        "M2_HORE": ("%Q0.3", None),
    }


@pytest.mark.parametrize("number", ["6.3.4", "6.3.5"])
def test_the_object_is_taken_from_under_the_press_while_the_ram_goes_back_up(number):
    """The scenario's premise, on the seeds the tests grade: the operator's hand comes after the first stroke's KS2
    and before the ram is back at KS1 (a removal on the way down would leave the textbook's stroke nothing to
    punch); the textbook's program then strokes no more and leaves the belt and the ram standing at KS1."""
    ex = get(number)
    for seed in (1, 2, 3):  # tests/course/test_seeds.py grades 1..20: there the premise failing fails the reference
        sim = ex.simulation(ex.reference.program(), TAKEN_FROM_THE_PRESS, seed=seed)
        sim.run()
        trace = sim.trace
        (removed,) = [e.t_ns for e in trace.events if e.kind == "part removed"]
        ks1, ks2 = trace.column("KS1").astype(bool), trace.column("KS2").astype(bool)
        now = int((trace.times <= removed).sum()) - 1
        bottom = int(ks2[: now + 1].nonzero()[0][-1])
        assert bottom < now and not ks1[bottom : now + 1].any() and trace.column("M2_HORE")[now], seed
        assert [p for _, p in strokes_of(trace)] == ["p1"], seed
        assert ks1[-1] and not trace.column("M1_VPRED")[-1] and not trace.column("M1_VZAD")[-1], seed
