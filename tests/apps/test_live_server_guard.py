"""The live server answers only its own page: a request naming another host (a DNS-rebinding page), a WebSocket
opened by another site's page, or one without the session's token is refused; nothing is written on a GET."""

from __future__ import annotations

import http.client
import json
import re
import socket

import pytest

from plcsim.apps.live.session import PANEL_DEMO

pytest.importorskip("uvicorn", reason="the live extra is not installed: pip install 'plcsim[live]'")
client = pytest.importorskip("websockets.sync.client", reason="the live extra is not installed")
InvalidStatus = pytest.importorskip("websockets.exceptions").InvalidStatus

EVIL = "http://evil.example"


@pytest.fixture
def panel(tmp_path):
    from plcsim.apps.live.server import open_live

    served = open_live("PANEL", PANEL_DEMO, port=0, paused=True, save_scenario=tmp_path / "saved.toml")
    yield served
    served.stop()


def _http(panel, method: str, path: str, headers: dict[str, str] | None = None) -> tuple[int, str]:
    conn = http.client.HTTPConnection("127.0.0.1", panel.port, timeout=10)
    try:
        conn.request(method, path, headers={"Host": f"127.0.0.1:{panel.port}", **(headers or {})})
        response = conn.getresponse()
        return response.status, response.read().decode("utf-8")
    finally:
        conn.close()


def _ws(panel, *, host: str | None = None, origin: str | None = None, token: str | None = None):
    """A WebSocket to the panel's server naming ``host`` (default its own) and sending ``origin`` and ``token``."""
    query = "" if token is None else f"?token={token}"
    sock = socket.create_connection(("127.0.0.1", panel.port), timeout=10)
    uri = f"ws://{host or f'127.0.0.1:{panel.port}'}/ws{query}"
    return client.connect(uri, sock=sock, origin=origin, proxy=None, open_timeout=10)


def test_the_page_carries_the_sessions_token_and_its_socket_works_with_it(panel):
    status, page = _http(panel, "GET", "/")
    assert status == 200
    token = re.search(r'<meta name="plcsim-token" content="([^"]+)">', page).group(1)
    assert token == panel.token and len(token) >= 32
    for host in (f"127.0.0.1:{panel.port}", f"localhost:{panel.port}"):
        with _ws(panel, host=host, origin=f"http://{host}", token=token) as ws:
            assert json.loads(ws.recv(timeout=10))["type"] == "layout"


@pytest.mark.parametrize(
    ("why", "options"),
    [
        ("another site's page", {"origin": EVIL}),
        ("a DNS-rebinding page", {"host": "evil.example:{port}", "origin": "http://evil.example:{port}"}),
        ("no token", {"token": None}),
        ("a wrong token", {"token": "guessed"}),
    ],
)
def test_a_websocket_from_anyone_but_the_page_is_refused(panel, why, options):
    given = {"token": panel.token, "origin": f"http://127.0.0.1:{panel.port}"}
    given.update({k: v.format(port=panel.port) if isinstance(v, str) else v for k, v in options.items()})
    with pytest.raises(InvalidStatus) as refused:
        _ws(panel, **given).close()
    assert refused.value.response.status_code == 403, why


@pytest.mark.parametrize("path", ["/", "/api/layout", "/api/scenario.toml", "/static/app.js"])
def test_a_request_naming_another_host_is_refused(panel, path):
    status, body = _http(panel, "GET", path, {"Host": f"evil.example:{panel.port}"})
    assert status == 403 and "127.0.0.1" in body


def test_reading_the_scenario_writes_nothing(panel, tmp_path):
    status, text = _http(panel, "GET", "/api/scenario.toml")
    assert status == 200 and "[session]" in text
    status, text = _http(panel, "GET", "/api/scenario.py")
    assert status == 200 and "SCENARIO = Scenario(" in text
    assert _http(panel, "GET", "/api/scenario.exe")[0] == 404
    assert not (tmp_path / "saved.toml").exists()


def test_saving_is_a_post_with_the_sessions_token(panel, tmp_path):
    saved = tmp_path / "saved.toml"
    assert _http(panel, "POST", "/api/save")[0] == 403
    assert _http(panel, "POST", "/api/save", {"X-Plcsim-Token": "guessed"})[0] == 403
    assert _http(panel, "POST", "/api/save", {"X-Plcsim-Token": panel.token, "Origin": EVIL})[0] == 403
    assert _http(panel, "GET", "/api/save", {"X-Plcsim-Token": panel.token})[0] == 405
    assert not saved.exists()
    status, body = _http(panel, "POST", "/api/save", {"X-Plcsim-Token": panel.token})
    assert status == 200 and json.loads(body)["path"] == str(saved) and saved.is_file()


def test_a_message_that_is_no_command_is_answered_not_raised():
    from plcsim.apps.live import LiveSession
    from plcsim.apps.live.runner import Runner

    runner = Runner(LiveSession("PANEL", PANEL_DEMO))
    for message in ([1, 2], "press", None, {"op": "do", "verb": "press", "target": "TL", "args": [1]}):
        assert runner.command(message)["type"] == "error"
    assert runner.session.recorded == []


def test_text_that_is_no_json_is_answered_and_the_socket_stays_open(panel):
    with _ws(panel, origin=f"http://127.0.0.1:{panel.port}", token=panel.token) as ws:
        assert json.loads(ws.recv(timeout=10))["type"] == "layout"
        ws.send("{not json")
        ws.send(json.dumps({"op": "digest"}))
        kinds: list[str] = []
        while "digest" not in kinds:  # the state frames in between do not count
            kinds += [kind for kind in [json.loads(ws.recv(timeout=10))["type"]] if kind != "state"]
        assert kinds == ["error", "digest"], kinds
