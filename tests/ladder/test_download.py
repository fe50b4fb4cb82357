"""Downloading a changed program into a live session without ending it: STOP -> load -> RUN, the machine
keeps running, an error names the file and line and changes nothing, and the saved session (with the
program's text in it) replays bit for bit."""

from __future__ import annotations

import os

import pytest

from plcsim.apps.live import LiveSession, Recording
from plcsim.apps.live.build import Target
from plcsim.core.errors import PlcError
from plcsim.frontends.python.program import Program

LAMP = "def OB1(t):\n    t.LED = t.TL\n"
INVERTED = "def OB1(t):\n    t.LED = not t.TL\n"


def test_a_download_swaps_the_logic_mid_run_and_the_saved_session_replays_bit_for_bit(tmp_path):
    program = tmp_path / "lamp.py"
    program.write_text(LAMP, encoding="utf-8")
    session = LiveSession("PANEL", program, seed=1)
    session.advance(20_000_000)
    assert session.sim.cpu.outputs["LED"] is False and not session.program_changed()
    program.write_text(INVERTED, encoding="utf-8")
    os.utime(program, ns=(1, 1))  # a save the page notices (mtime differs)
    assert session.program_changed()
    session.download()
    session.advance(30_000_000)
    assert session.sim.cpu.outputs["LED"] is True  # the inverted program runs
    assert session.sim.cpu.mode == "RUN" and not session.program_changed()
    assert any("download" in d.event for d in session.sim.cpu.diagnostics)
    session.do("press", "TL")
    session.advance(20_000_000)
    assert session.sim.cpu.outputs["LED"] is False
    rec = session.recording()
    assert [a.verb for a in rec.actions] == ["download", "press"]
    again = Recording.from_toml(rec.to_toml(), "saved.toml")
    assert again.actions[0].args["program"] == INVERTED
    sim = Target.find("PANEL").simulation(Program(LAMP, str(program)), again.scenario(), seed=again.seed)
    sim.run()
    assert sim.trace.digest() == session.sim.trace.digest()
    assert session.replay().trace.digest() == session.sim.trace.digest()  # from the program it started with


def test_a_program_that_does_not_compile_is_refused_with_its_line_and_the_cpu_runs_on(tmp_path):
    program = tmp_path / "lamp.py"
    program.write_text(LAMP, encoding="utf-8")
    session = LiveSession("PANEL", program, seed=1)
    session.advance(10_000_000)
    program.write_text("def OB1(t):\n    t.LED = t.NO_SUCH_TAG\n", encoding="utf-8")
    with pytest.raises(PlcError, match=r"lamp.py, line 2: .*NO_SUCH_TAG"):
        session.download()
    session.advance(10_000_000)
    assert session.sim.cpu.mode == "RUN" and session.recorded == []


@pytest.mark.parametrize("suffix", [".toml", ".py"])
def test_a_saved_session_replays_from_its_first_program_after_the_file_was_edited(tmp_path, capsys, suffix):
    """The student edits, downloads, saves the session, then edits the file again: the replay starts from the
    program as it was when the session began (kept in the scenario file) and says that the file changed."""
    from plcsim.apps.cli import main

    program = tmp_path / "lamp.py"
    program.write_text(LAMP, encoding="utf-8")
    session = LiveSession("PANEL", program, seed=1)
    session.advance(20_000_000)
    session.download(INVERTED)
    session.do("press", "TL")
    session.advance(30_000_000)
    saved = session.save(tmp_path / f"session{suffix}")
    program.write_text("def OB1(t):\n    t.LED = True\n", encoding="utf-8")  # the student goes on editing
    assert main(["run", "PANEL", "--program", str(program), "--scenario", str(saved)]) == 0
    out = capsys.readouterr().out
    assert f"trace digest {session.sim.trace.digest()[:16]}" in out
    assert "has changed since, so the replay starts from the text as it was" in " ".join(out.split())


def test_a_session_without_a_download_keeps_no_copy_of_the_program(tmp_path):
    program = tmp_path / "lamp.py"
    program.write_text(LAMP, encoding="utf-8")
    session = LiveSession("PANEL", program, seed=1)
    session.advance(20_000_000)
    assert session.recording().first_program is None and "first_program" not in session.recording().to_toml()
