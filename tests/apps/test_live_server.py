"""The live panel's server and pacing, without a browser: a WebSocket client speaks the page's protocol."""

from __future__ import annotations

import json
import time

import pytest

from plcsim.apps.live import LiveSession, Recording
from plcsim.apps.live.build import Target
from plcsim.apps.live.runner import Runner
from plcsim.apps.live.session import PANEL_DEMO

MS = 1_000_000


def test_the_runner_paces_by_the_wall_time_it_is_given():
    runner = Runner(LiveSession("PANEL", PANEL_DEMO), speed=2.0)
    runner.tick(0.1)
    assert runner.session.now == 200 * MS  # 0.1 s of wall time at ×2
    runner.command({"op": "speed", "value": 0.1})
    runner.tick(0.05)
    assert runner.session.now == 205 * MS
    runner.command({"op": "pause"})
    runner.tick(1.0)
    assert runner.session.now == 205 * MS
    runner.command({"op": "scan"})  # one OB1 scan: 1 ms cycles on this rig
    assert runner.session.now == 206 * MS and runner.paused


def test_as_fast_as_possible_stops_at_the_frame_deadline():
    runner = Runner(LiveSession("PANEL", PANEL_DEMO), speed=None)
    start = time.perf_counter()
    runner.tick(0.02, deadline=start + 0.05)
    assert runner.session.now > 0
    assert time.perf_counter() - start < 1.0  # it gave control back (a bound, not a timing measurement)


def test_a_bad_command_is_answered_not_raised():
    runner = Runner(LiveSession("PANEL", PANEL_DEMO))
    assert runner.command({"op": "do", "verb": "press", "target": "NOPE"})["type"] == "error"
    assert runner.command({"op": "fly"}) == {"type": "error", "message": "unknown command 'fly'"}
    assert runner.command({"op": "speed", "value": 1000})["type"] == "error"
    assert runner.session.recorded == []


def test_the_websocket_protocol_presses_lights_saves_and_replays(tmp_path):
    pytest.importorskip("uvicorn", reason="the live extra is not installed: pip install 'plcsim[live]'")
    from websockets.sync.client import connect

    from plcsim.apps.live.server import open_live

    program = tmp_path / "lamp.py"
    program.write_text(PANEL_DEMO, encoding="utf-8")
    panel = open_live("PANEL", program, port=0, save_scenario=tmp_path / "saved.toml")
    try:
        with connect(f"ws://127.0.0.1:{panel.port}/ws?token={panel.token}", open_timeout=10) as ws:
            first = json.loads(ws.recv(timeout=10))
            assert first["type"] == "layout" and "TL" in [c["name"] for c in first["controls"]]
            ws.send(json.dumps({"op": "do", "verb": "press", "target": "TL"}))
            lit = _wait(ws, lambda m: m["type"] == "state" and m["watch"]["LED"] is True)
            ws.send(json.dumps({"op": "release", "target": "TL"}))
            _wait(ws, lambda m: m["type"] == "state" and m["watch"]["LED"] is False and m["t_ns"] > lit["t_ns"])
            ws.send(json.dumps({"op": "save"}))
            saved = _wait(ws, lambda m: m["type"] == "saved")
    finally:
        panel.stop()
    assert saved["path"] == str(tmp_path / "saved.toml") and saved["actions"] == 2
    rec = Recording.from_toml((tmp_path / "saved.toml").read_text(encoding="utf-8"))
    sim = Target.find("PANEL").simulation(program, rec.scenario(), seed=rec.seed)
    sim.run()
    assert sim.trace.digest() == saved["digest"]


def _wait(ws, condition, timeout_s: float = 20.0) -> dict:
    """The first message that meets ``condition`` (the page's frames come every 40 ms)."""
    end = time.monotonic() + timeout_s
    while time.monotonic() < end:
        message = json.loads(ws.recv(timeout=timeout_s))
        if message.get("type") == "error":
            raise AssertionError(message["message"])
        if condition(message):
            return message
    raise AssertionError("no such message in time")


def test_plcsim_live_ends_from_the_page_saving_the_scenario_and_the_recording(tmp_path, capsys):
    pytest.importorskip("uvicorn", reason="the live extra is not installed: pip install 'plcsim[live]'")
    import socket
    import threading

    from websockets.sync.client import connect

    from plcsim.apps.cli import main

    with socket.socket() as probe:
        probe.bind(("127.0.0.1", 0))
        port = probe.getsockname()[1]
    program = tmp_path / "lamp.py"
    program.write_text(PANEL_DEMO, encoding="utf-8")
    saved, rrd = tmp_path / "session.py", tmp_path / "session.rrd"
    argv = ["live", "PANEL", "--program", str(program), "--port", str(port), "--no-browser", "--paused"]
    argv += ["--save-scenario", str(saved), "--rrd", str(rrd)]
    result: list[int] = []
    cli = threading.Thread(target=lambda: result.append(main(argv)))
    cli.start()
    try:
        ws = _connect(connect, port)
        with ws:
            json.loads(ws.recv(timeout=10))
            ws.send(json.dumps({"op": "do", "verb": "press", "target": "TL"}))
            for _ in range(3):  # paused: one scan at a time
                ws.send(json.dumps({"op": "scan"}))
            ws.send(json.dumps({"op": "end"}))
            ended = _wait(ws, lambda m: m["type"] == "ended")
    finally:
        cli.join(timeout=30)
    assert result == [0]
    assert ended["t_ns"] == 3 * MS and ended["path"] == str(saved)
    assert 'press("TL", t="0ms")' in saved.read_text(encoding="utf-8")
    assert rrd.stat().st_size > 0
    out = capsys.readouterr().out
    assert f"trace digest {ended['digest'][:16]}" in out


def test_the_notebook_handle_shows_the_page_inline(tmp_path):
    pytest.importorskip("uvicorn", reason="the live extra is not installed: pip install 'plcsim[live]'")
    from plcsim.apps.live import open_live

    panel = open_live("PANEL", PANEL_DEMO, port=0, paused=True)
    try:
        assert f'<iframe src="{panel.url}"' in panel._repr_html_()
        assert repr(panel) == f"<LivePanel PANEL at {panel.url}>"
    finally:
        panel.stop()


def _connect(connect, port: int):
    """The CLI's server comes up within a moment of its thread starting; the socket needs the token its page holds."""
    import http.client
    import re

    end = time.monotonic() + 30
    while True:
        try:
            conn = http.client.HTTPConnection("127.0.0.1", port, timeout=10)
            conn.request("GET", "/")
            page = conn.getresponse().read().decode("utf-8")
            conn.close()
            token = re.search(r'<meta name="plcsim-token" content="([^"]+)">', page).group(1)
            return connect(f"ws://127.0.0.1:{port}/ws?token={token}", open_timeout=10)
        except OSError:
            if time.monotonic() > end:
                raise
            time.sleep(0.1)


def test_the_page_grades_an_exercise_session_on_its_trace_so_far():
    from exercises import get

    runner = Runner(LiveSession("4.3.7", str(get("4.3.7").reference.path), scenario="jam", seed=2))
    runner.session.advance(16_000 * MS)
    graded = runner.command({"op": "grade"})
    assert graded["type"] == "graded" and graded["t_ns"] == 16_000 * MS
    assert len(graded["results"]) >= 5 and all(r["passed"] for r in graded["results"]), graded["results"]
    assert Runner(LiveSession("PANEL", PANEL_DEMO)).command({"op": "grade"})["results"] == []
