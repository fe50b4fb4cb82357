"""What a page (or a student's file) sends the live session is untrusted: every name is checked against the rig's
vocabulary before it is recorded, and the saved scenario is written by a TOML writer and as Python literals, so
that no name can become code (``.py``) or an action of its own (``.toml``)."""

from __future__ import annotations

import contextlib
import tomllib

import pytest

from plcsim.apps.live import LiveSession, Recording, load_scenario_file
from plcsim.apps.live.build import Target
from plcsim.core.errors import PlcError
from plcsim.scenario.verbs import ScenarioError, place

MS = 1_000_000
SORT_REFERENCE = "exercises/solutions/4_3_17/reference.py"
CONVEYOR = "def OB1(t):\n    t.D1 = t.S1\n"


def _code_in_a_name(marker) -> str:
    """A part property's name that, written unquoted into a ``.py``, creates ``marker`` when the file is run."""
    return f"colour=__import__('pathlib').Path({str(marker)!r}).touch() or 2, extra"


ACTION_IN_A_NAME = 'x = 1\n\n[[action]]\nt = "1ms"\nverb = "stop_cpu"\ny'
"""A part property's name that, written unquoted into a ``.toml``, adds an action of its own."""


def test_a_part_property_the_rig_does_not_declare_is_refused_before_it_is_recorded(tmp_path):
    session = LiveSession("4.3.17", SORT_REFERENCE, seed=3)
    refusals = {
        _code_in_a_name(tmp_path / "ran"): r"part property name .* is not a Python name",
        ACTION_IN_A_NAME: r"part property name .* is not a Python name",
        "t": r"part property name 't' is the action's own",
        "size": r"no part property 'size'; valid: color, colour, colour_raw",
    }
    for name, refusal in refusals.items():
        with pytest.raises(ScenarioError, match=refusal):
            session.do("place", station="OS1", **{name: 2})
    assert session.recorded == []
    session.do("place", station="OS1", colour=2)  # declared by the colour sorter: recorded
    assert [a.verb for a in session.recorded] == ["place"]


def test_an_argument_a_rig_verb_does_not_name_is_refused():
    session = LiveSession("4.3.17", SORT_REFERENCE, seed=3)
    with pytest.raises(ScenarioError, match=r"set_ambient FARBA: no argument 'x=1, y'; its arguments: offset"):
        session.do("set_ambient", "FARBA", offset=1.0, **{"x=1, y": 2})
    assert session.recorded == []


def test_a_number_that_no_file_can_hold_is_refused():
    session = LiveSession("CONV1", CONVEYOR, seed=1)
    with pytest.raises(ScenarioError, match=r"mm=inf: a number must be finite"):
        session.do("shift", "S2", mm=float("inf"))
    assert session.recorded == []


def test_a_hostile_name_in_a_python_recording_never_runs(tmp_path):
    """Even an action that got past the checks (built by hand here) cannot write code into the ``.py``."""
    marker = tmp_path / "ran"
    action = place("p1", at="OS1", t=0, noise=False)
    action.args["properties"][_code_in_a_name(marker)] = 2
    rec = Recording("4.3.17", seed=1, actions=[action], ended_ns=10 * MS)
    with contextlib.suppress(PlcError):
        rec.save(tmp_path / "hostile.py")
        load_scenario_file(tmp_path / "hostile.py")  # what `plcsim run --scenario hostile.py` does
    assert not marker.exists()
    with pytest.raises(ScenarioError, match=r"property name .* is not a Python name"):
        rec.to_python()


def test_a_hostile_name_in_a_toml_recording_adds_no_action():
    """Written, a name that is no property name is refused; read, one quoted in the file is refused too."""
    for name in (ACTION_IN_A_NAME, "verb"):
        action = place("p1", at="OS1", t=0, noise=False, colour=2)
        action.args["properties"][name] = "stop_cpu"
        rec = Recording("4.3.17", seed=1, actions=[action], ended_ns=10 * MS)
        with pytest.raises(ScenarioError, match=r"part property name .* is (not a Python name|the action's own)"):
            rec.to_toml()
    quoted = '"x = 1\\n[[action]]\\nverb = \\"stop_cpu\\"" = 2'
    text = f"[session]\ntarget = '4.3.17'\nseed = 1\nended = '2s'\n[[action]]\nt = '1ms'\nverb = 'place'\n{quoted}\n"
    assert len(tomllib.loads(text)["action"]) == 1
    with pytest.raises(ScenarioError, match=r"hostile\.toml: .*property name .* is not a Python name"):
        Recording.from_toml(text + "station = 'OS1'\n", "hostile.toml")


@pytest.mark.parametrize("suffix", [".toml", ".py"])
def test_odd_part_names_and_texts_replay_exactly(tmp_path, suffix):
    """A part may be called anything the page sends: quotes, a newline, backslashes; it is written as a literal
    and replays to the same trace."""
    session = LiveSession("CONV1", CONVEYOR, seed=2)
    odd = "p\"1'\n\\[[action]]\x7f é"
    session.do("place", odd, station="S1")
    session.advance(1500 * MS)
    session.do("shift", "S2", mm=2.5)
    session.advance(500 * MS)
    session.do("knock_off", odd)
    session.advance(500 * MS)
    path = tmp_path / f"odd{suffix}"
    session.save(path)
    target = Target.find("CONV1")
    scenario, seed, _ = load_scenario_file(path, base=target.base, rig_verbs=target.verbs())
    assert [a.target for a in scenario.actions if a.verb != "shift"] == [odd, odd]
    sim = target.simulation(session.program, scenario, seed=seed)
    sim.run()
    assert sim.trace.digest() == session.sim.trace.digest()


def test_a_toml_scenario_cannot_name_an_undeclared_property_either(tmp_path):
    path = tmp_path / "student.toml"
    path.write_text(
        "[session]\ntarget = '4.3.17'\nseed = 1\nended = '2s'\n"
        "[[action]]\nt = '1ms'\nverb = 'place'\ntarget = 'p1'\nstation = 'OS1'\nnoise = true\nsize = 3\n",
        encoding="utf-8",
    )
    target = Target.find("4.3.17")
    scenario, seed, _ = load_scenario_file(path, base=target.base, rig_verbs=target.verbs())
    with pytest.raises(ScenarioError, match=r"no part property 'size'; valid: color, colour, colour_raw"):
        target.simulation(SORT_REFERENCE, scenario, seed=seed)


@pytest.mark.parametrize("target", ["PANEL", "4.3.7"])
def test_a_saved_scenario_longer_than_the_target_allows_is_refused(tmp_path, capsys, target):
    """``ended = "10 000 h"`` would replay without bound: refused unless ``--seconds`` bounds the run."""
    from plcsim.apps.cli import EXIT_USAGE, main

    if target == "PANEL":
        program = tmp_path / "lamp.py"
        program.write_text("def OB1(t):\n    t.LED = t.TL\n", encoding="utf-8")
    else:
        from exercises import get

        program = get(target).reference.path
    path = tmp_path / "endless.toml"
    path.write_text(f"[session]\ntarget = '{target}'\nseed = 1\nended = '10 000 h'\n", encoding="utf-8")
    argv = ["run", target, "--program", str(program), "--scenario", str(path)]
    assert main(argv) == EXIT_USAGE
    said = " ".join(capsys.readouterr().err.split())
    assert f"{path}: the scenario lasts 36000000 s" in said and "may last 3600 s" in said, said
    assert "--seconds" in said
    assert main([*argv, "--seconds", "0.05"]) != EXIT_USAGE  # the teacher bounds the run: 50 ms
    assert "for 0.05 s simulated" in capsys.readouterr().out
