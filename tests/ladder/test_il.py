"""A Tecomat IL program's online view: each line with A0 and A1 after it in the last pass (STL monitoring),
and watching it changes nothing in the run (the trace digest is the same)."""

from __future__ import annotations

from exercises import get
from plcsim.apps.live import LiveSession
from plcsim.ladder.il import IlMonitor


def _session():
    exercise = get("T-01")
    session = LiveSession("T-01", exercise.reference.path, seed=1)
    return session


def test_each_line_shows_the_accumulator_after_it_and_the_latch_holds_the_motor():
    session = _session()
    assert session.ladder_svg() is not None  # the Program card attaches the online view
    monitor = session._ladder
    session.do("press", "START")
    session.advance(50_000_000)
    session.release("START")
    session.advance(50_000_000)
    rows = {text.split(";")[0].strip(): values for _, text, values in monitor.lines(session.program.text)}
    assert rows["LD  START"][0] == 0  # released: A0 is 0
    assert rows["OR  MOTOR"][0] == 0xFFFF  # the held contact: A0 all ones
    assert rows["WR  MOTOR"][0] == 0xFFFF
    assert rows["#def START x0.0"] is None  # a declaration runs nothing
    svg = session.ladder_svg()
    assert svg is not None and 'data-a0="65535"' in svg and "LD  START" in svg


def test_watching_an_instruction_list_leaves_the_run_bit_for_bit_the_same():
    plain, watched = _session(), _session()
    IlMonitor(watched.sim.cpu).attach()
    for session in (plain, watched):
        session.do("press", "START")
        session.advance(30_000_000)
        session.release("START")
        session.advance(200_000_000)
    assert plain.sim.trace.digest() == watched.sim.trace.digest()
