"""The live session's core, without a server or a browser: actions at simulated instants, recorded, replayed.

The promise under test: whatever the student does live, saved as a scenario (.toml or .py) and replayed afresh,
gives the same trace digest; and an action applied live acts exactly when a scenario action at that time would.
"""

from __future__ import annotations

import pytest

from exercises.ex_4_3_16 import EXERCISE
from plcsim.apps.live import LiveSession, Recording, load_scenario_file
from plcsim.apps.live.build import Target
from plcsim.apps.live.session import PANEL_DEMO
from plcsim.core.errors import PlcError
from plcsim.scenario.verbs import ScenarioError

CONVEYOR = """\
def OB1(t):
    if t.S1:
        t.D1 = True
    if t.S2:
        t.D1 = False
"""
MS = 1_000_000


def replayed_digest(session: LiveSession, path) -> str:
    """Save the session to ``path``, read the file back as the CLI does, run it afresh: the trace digest."""
    session.save(path)
    target = Target.find(session.target.name)
    scenario, seed, _ = load_scenario_file(path, base=target.base, rig_verbs=target.verbs())
    sim = target.simulation(session.program, scenario, seed=seed)
    sim.run()
    assert sim.now == session.now
    return sim.trace.digest()


def test_a_press_reaches_the_program_at_its_instant():
    session = LiveSession("PANEL", PANEL_DEMO, seed=1)
    session.advance(100 * MS)
    session.do("press", "TL")
    session.advance(1 * MS)  # one step: the scan starting at 100 ms reads the button, its end writes LED
    assert session.sim.cpu.read("LED") is True
    trace = session.sim.trace
    assert trace.rises("TL")[0] == 100 * MS  # the input changes with the scan that started at the press


def test_a_quick_click_lasts_two_scans(tmp_path):
    session = LiveSession("PANEL", PANEL_DEMO, seed=1)
    session.advance(10 * MS)
    session.do("press", "TL")
    release = session.release("TL")  # no time passed: the release comes two cycles later
    assert release.t.lo_ns == 10 * MS + session.min_hold_ns == 12 * MS
    assert session.recording().actions == []  # neither has acted yet: the step at 10 ms applies the press
    session.advance(20 * MS)
    intervals = session.sim.trace.intervals("LED")
    assert intervals[0][0] > 10 * MS and intervals[0][1] is not None
    assert [a.verb for a in session.recording().actions] == ["press", "release"]
    assert replayed_digest(session, tmp_path / "click.toml") == session.sim.trace.digest()


@pytest.mark.parametrize("suffix", [".toml", ".py"])
def test_a_conveyor_session_replays_bit_for_bit(tmp_path, suffix):
    session = LiveSession("CONV1", CONVEYOR, seed=3)
    session.advance(300 * MS)
    session.do("place", station="S1")  # p1, with the seeded pose noise
    session.advance(2500 * MS)
    session.do("jam", "p1")
    session.advance(700 * MS)
    session.do("unjam", "p1")
    session.do("stick", "S2", value=False)
    session.advance(4000 * MS)
    session.do("clear", "S2")
    session.write_text("D1", "0", forced=True)
    session.advance(500 * MS)
    session.do("unforce", "D1")
    session.advance(3000 * MS)
    kinds = [e.kind for e in session.sim.trace.events if e.source == "scenario"]
    assert kinds == ["place", "jam", "unjam", "stick", "clear", "force", "unforce"]
    assert session.sim.trace.rises("D1").size >= 1
    assert replayed_digest(session, tmp_path / f"conveyor{suffix}") == session.sim.trace.digest()


def test_chunks_of_any_size_give_the_same_trace():
    """The server advances by what the wall clock allows; the trace must not depend on it."""
    digests = set()
    for chunks in ([10_000 * MS], [7 * MS] * 1428 + [4 * MS], [333 * MS] * 30 + [10 * MS]):
        session = LiveSession("CONV1", CONVEYOR, seed=5)
        session.do("place", station="S1")
        for ns in chunks:
            session.advance(ns)
        assert session.now == 10_000 * MS
        digests.add(session.sim.trace.digest())
    assert len(digests) == 1


def test_a_session_on_an_exercise_scenario_replays_and_grades(tmp_path):
    session = LiveSession("4.3.7", _reference("4.3.7"), scenario="jam", seed=2)
    session.advance(5000 * MS)
    session.do("write", "ACK", value=True)  # an early, pointless acknowledge: recorded like any click
    session.advance(11_000 * MS)
    rec = session.recording()
    assert rec.base == "jam" and rec.name == "jam" and [a.verb for a in rec.actions] == ["write"]
    assert replayed_digest(session, tmp_path / "jam.toml") == session.sim.trace.digest()
    assert replayed_digest(session, tmp_path / "jam.py") == session.sim.trace.digest()
    failed = [v.message for _, v in session.grade() if not v.passed]
    assert any("after ACK rises at 5 s" in m for m in failed), failed  # the checks read the live trace


def test_a_session_that_only_watches_grades_as_the_scenario_does():
    session = LiveSession("4.3.7", _reference("4.3.7"), scenario="jam", seed=2)
    session.advance(16_000 * MS)  # the scenario's duration
    results = session.grade()
    assert len(results) >= 5 and all(v.passed for _, v in results), [v.message for _, v in results if not v.passed]


def test_saved_midway_the_base_scenario_is_cut_where_the_session_ended(tmp_path):
    session = LiveSession("4.3.7", _reference("4.3.7"), scenario="jam", seed=2)
    session.advance(3000 * MS)  # the jam scenario's acknowledgement at 13..14 s has not happened
    assert replayed_digest(session, tmp_path / "early.toml") == session.sim.trace.digest()
    assert replayed_digest(session, tmp_path / "early.py") == session.sim.trace.digest()


@pytest.mark.parametrize("suffix", [".toml", ".py"])
def test_the_rigs_own_verbs_and_a_parts_colour_are_recorded_and_replay(tmp_path, suffix):
    """On the colour sorter (4.3.17's reference): daylight on the colour sensor, a red part placed at OS1, then the
    compressor failing before the part reaches piston 2: the piston's pulse cannot move it, the program frees the
    position all the same and the belt stops with the part on it, live and in the replay."""
    session = LiveSession("4.3.17", "exercises/solutions/4_3_17/reference.py", seed=3)
    verbs = {v["verb"]: v for v in session.layout()["rig_verbs"]}
    assert verbs["set_ambient"]["targets"] == ["FARBA"] and verbs["set_ambient"]["args"] == ["offset"]
    assert verbs["fail_compressor"]["targets"] == ["Kompresor"] and "interrupt" not in verbs  # an S7 program
    session.do("set_ambient", "FARBA", offset=1500.0)
    session.do("place", station="OS1", colour=2)
    session.advance(5000 * MS)
    session.do("fail_compressor", "Kompresor")
    session.advance(9000 * MS)
    trace = session.sim.trace
    assert [e.kind for e in trace.events if e.kind in ("part in bin", "compressor failed")] == ["compressor failed"]
    assert trace.column("DATA.POZ4_FARBA2").max() == 2 and trace.intervals("Piest2_Farba2")  # typed red, pushed
    part = session.sim.plant.parts["p1"]
    assert part.props["colour"] == 2 and 360 < part.body.position.x < 390 and not trace.column("D1_VPRED")[-1]
    assert replayed_digest(session, tmp_path / f"sort{suffix}") == session.sim.trace.digest()


def test_the_tecomats_own_verbs_are_offered_on_an_il_program_and_replay(tmp_path):
    """A Tecomat program (t-05's .il reference) brings the controller's verbs: an interrupt source and the clock."""
    session = LiveSession("t-05", "exercises/solutions/T_05/reference.il")
    verbs = {v["verb"]: v for v in session.layout()["rig_verbs"]}
    assert verbs["interrupt"]["targets"] == [str(k) for k in range(1, 9)] and verbs["set_clock"]["targets"] == []
    session.do("set_clock", "07:59:30")
    session.advance(1000 * MS)
    session.do("interrupt", "1")
    session.advance(100 * MS)
    assert [e.kind for e in session.sim.trace.events if e.source == "scenario"] == ["set_clock", "interrupt"]
    assert replayed_digest(session, tmp_path / "tecomat.toml") == session.sim.trace.digest()


def test_a_verb_of_another_rig_is_refused_with_the_verbs_there_are():
    session = LiveSession("4.3.17", "exercises/solutions/4_3_17/reference.py")
    with pytest.raises(ScenarioError, match=r"cannot record 'jam_piston' here; verbs: .*set_ambient, fail_compressor"):
        session.do("jam_piston", "P1")
    assert session.recorded == []


def test_a_name_the_run_lacks_is_refused_and_not_recorded():
    session = LiveSession("PANEL", PANEL_DEMO, seed=1)
    with pytest.raises(ScenarioError, match=r"live session action 1: .*press TX at 0 ns: no button or switch 'TX';"):
        session.do("press", "TX")
    with pytest.raises(PlcError, match="LED is a bool: 'maybe' is not one"):
        session.write_text("LED", "maybe")
    with pytest.raises(PlcError, match="TL is not forced"):
        session.do("unforce", "TL")
    with pytest.raises(ScenarioError, match="no station 'S1'; valid: none"):
        session.do("place", station="S1")
    assert session.recorded == [] and session.recording().actions == []


def test_a_bad_recording_names_the_file_and_what_it_needs():
    with pytest.raises(ScenarioError, match=r"mine\.toml: not a plcsim live recording \(missing key 'session'\)"):
        Recording.from_toml("[[action]]\nt = '1ms'\nverb = 'press'\n", "mine.toml")
    with pytest.raises(ScenarioError, match=r"mine\.toml: .*cannot record 'dance'"):
        Recording.from_toml(
            "[session]\ntarget='PANEL'\nseed=1\nended='5ms'\n[[action]]\nt='1ms'\nverb='dance'\n", "mine.toml"
        )


def test_the_page_state_shows_the_lamp_and_the_watch_table():
    session = LiveSession("PANEL", PANEL_DEMO, seed=1)
    layout = session.layout()
    assert {c["name"]: c["kind"] for c in layout["controls"]}["PREPINAC"] == "switch"
    assert {c["name"]: c["kind"] for c in layout["controls"]}["TL"] == "button"
    session.do("press", "TL")
    session.advance(2 * MS)
    state = session.state()
    lamp = next(d for d in state["dynamic"] if d[0] == "panel/lamps/LED")
    assert state["watch"]["LED"] is True and state["mode"] == "RUN"
    assert lamp[3] != [70, 70, 70]  # lit: no longer the dark grey of an unlit lamp


def _reference(number: str) -> str:
    from exercises import get

    return str(get(number).reference.path)


def test_the_cli_replays_a_saved_session_with_its_seed(tmp_path, capsys):
    from plcsim.apps.cli import main

    program = tmp_path / "lamp.py"
    program.write_text(PANEL_DEMO, encoding="utf-8")
    session = LiveSession("PANEL", program, seed=7)
    session.advance(50 * MS)
    session.toggle("PREPINAC")
    session.do("press", "TL")
    session.advance(30 * MS)
    session.save(tmp_path / "s.toml")
    assert main(["run", "PANEL", "--program", str(program), "--scenario", str(tmp_path / "s.toml")]) == 0
    assert f"seed 7, trace digest {session.sim.trace.digest()[:16]}" in capsys.readouterr().out


def test_saving_midway_does_not_change_what_follows(tmp_path):
    session = LiveSession("CONV1", CONVEYOR, seed=4)
    session.do("place", station="S1")
    session.advance(1500 * MS)
    first = replayed_digest(session, tmp_path / "first.toml")
    assert first == session.sim.trace.digest()
    _ = session.state()  # a page frame in between
    session.do("knock_off", "p1")
    session.advance(2000 * MS)
    assert replayed_digest(session, tmp_path / "second.toml") == session.sim.trace.digest() != first


def test_an_exercise_s_hmi_tags_are_offered_as_controls_and_written_by_them():
    """4.3.16's HMI bits live in DB_SKIP: the page offers AUTO as a switch, MAN_HORE as a button, and writes them."""
    session = LiveSession(Target("4.3.16", exercise=EXERCISE), EXERCISE.reference.path, seed=1)
    controls = {c["name"]: c["kind"] for c in session.layout()["controls"]}
    assert controls["DB_SKIP.AUTO"] == "hmi switch" and controls["DB_SKIP.MAN_HORE"] == "hmi button"
    assert {v["verb"] for v in session.layout()["rig_verbs"]} == {"fill", "discharge"}
    session.write_text("DB_SKIP.MAN_HORE", "1")
    session.advance(500 * MS)
    assert session.sim.cpu.read("START_HORE") is True and session.state()["watch"]["DB_SKIP.MAN_HORE"] is True


def test_only_parts_still_on_the_machine_are_offered_verbs():
    """On the colour sorter: a part pushed into its bin, and one taken away, get no remove/jam buttons on the page;
    the one still riding does."""
    session = LiveSession("4.3.17", "exercises/solutions/4_3_17/reference.py", seed=3)
    events = session.sim.trace.events
    session.do("place", station="OS1", colour=2)
    session.advance(4000 * MS)
    session.do("place", station="OS1", colour=1)
    session.advance(500 * MS)
    session.do("remove", "p2")
    session.do("place", station="OS1", colour=3)
    session.advance(20_000 * MS, stop=lambda: any(e.kind == "part in bin" for e in events))
    assert [(e.kind, e.part) for e in events if e.kind in ("part in bin", "part removed")] == [
        ("part removed", "p2"),
        ("part in bin", "p1"),
    ]
    assert "p1" in session.sim.plant.parts  # just in its bin: the plant still simulates it
    assert sorted(session.state()["parts"]) == ["p3"]
