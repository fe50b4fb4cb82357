"""The live page's server: Starlette (routes, static files, a WebSocket) served by uvicorn on a local port.

Why these: Starlette is a small, well-kept ASGI toolkit whose WebSocket and static-file support are all this page
needs, and uvicorn its usual server; both are pure Python and install on Windows, macOS and Linux. The page
(``static/``: plain JavaScript and SVG, no build step, no CDN) is shipped in the package, so it works offline.

One WebSocket per open page: the server sends the layout once, then the state at up to 25 frames a second; the page
sends commands (see :meth:`plcsim.apps.live.runner.Runner.command`).

It answers its own page only (:class:`Guard`): a request naming another host than the one it serves (a DNS-rebinding
page) is refused, and so is a WebSocket opened by another site's page or without the session's token, which the page
gets when it loads; a write (``POST /api/save``) needs the token too, and a ``GET`` writes nothing.
"""

from __future__ import annotations

import asyncio
import contextlib
import json
import mimetypes
import os
import secrets
import socket
import threading
import time
from pathlib import Path
from typing import Any

from plcsim.apps.live.runner import Runner
from plcsim.apps.live.session import LiveSession
from plcsim.core.errors import PlcError

STATIC = Path(__file__).parent / "static"
mimetypes.add_type("text/javascript", ".js")  # Windows' registry may map .js to text/plain, which browsers refuse
mimetypes.add_type("text/css", ".css")
SEND_EVERY_S = 0.04
"""The page's frame period (25 frames a second)."""
TOKEN_HEADER = "X-Plcsim-Token"
"""The header a write (``POST /api/save``) carries the session's token in; the WebSocket carries it as ``?token=``."""
LOCAL_NAMES = ("127.0.0.1", "localhost")
"""The names the page may be opened by, besides the address served."""


def require_server() -> None:
    """Refuse clearly where the ``live`` extra is not installed."""
    import importlib.util

    missing = [m for m in ("starlette", "uvicorn", "websockets") if importlib.util.find_spec(m) is None]
    if missing:
        raise PlcError(f"the live panel needs {', '.join(missing)}: pip install 'plcsim[live]'")


def make_app(runner: Runner, token: str, served: list[str]) -> Any:
    """The Starlette application serving ``runner``'s session to the page that holds ``token``, on the addresses
    ``served`` (``host:port``, as a browser names them in ``Host``)."""
    require_server()
    from starlette.applications import Starlette
    from starlette.middleware import Middleware
    from starlette.responses import HTMLResponse, JSONResponse, PlainTextResponse
    from starlette.routing import Mount, Route, WebSocketRoute
    from starlette.staticfiles import StaticFiles
    from starlette.websockets import WebSocketDisconnect

    page = (STATIC / "index.html").read_text(encoding="utf-8")
    page = page.replace("</head>", f'  <meta name="plcsim-token" content="{token}">\n</head>', 1)

    async def index(_request: Any) -> Any:
        return HTMLResponse(page, headers={"Cache-Control": "no-store"})

    async def layout(_request: Any) -> Any:
        with runner.lock:
            return JSONResponse(runner.session.layout())

    async def recording(request: Any) -> Any:
        """The recording so far as text (``.toml`` or ``.py``); it writes nothing."""
        kind = request.path_params["kind"]
        if kind not in ("toml", "py"):
            return PlainTextResponse("the recording is /api/scenario.toml or /api/scenario.py", status_code=404)
        with runner.lock:
            rec = runner.session.recording()
            text = rec.to_toml() if kind == "toml" else rec.to_python()
        return PlainTextResponse(text, media_type="text/plain")

    async def save(request: Any) -> Any:
        """Write ``--save-scenario`` (the page's own token only)."""
        if not secrets.compare_digest(request.headers.get(TOKEN_HEADER, ""), token):
            return PlainTextResponse(f"saving needs the session's token in {TOKEN_HEADER}", status_code=403)
        return JSONResponse(await asyncio.to_thread(runner.save))

    async def stream(ws: Any) -> None:
        if not secrets.compare_digest(ws.query_params.get("token", ""), token):
            await ws.close(code=1008)  # before the handshake: the client is answered 403
            return
        await ws.accept()
        with runner.lock:
            await ws.send_text(json.dumps({"type": "layout", **runner.session.layout()}))

        async def send_frames() -> None:
            seen = -1
            while True:
                if runner.version != seen:
                    seen = runner.version
                    await ws.send_text(json.dumps({"type": "state", **runner.snapshot}))
                await asyncio.sleep(SEND_EVERY_S)

        sender = asyncio.create_task(send_frames())
        try:
            while True:
                try:
                    message = json.loads(await ws.receive_text())
                except ValueError as exc:
                    await ws.send_text(json.dumps({"type": "error", "message": f"not a JSON command: {exc}"}))
                    continue
                reply = await asyncio.to_thread(runner.command, message)
                if reply is not None:
                    await ws.send_text(json.dumps(reply))
        except (WebSocketDisconnect, RuntimeError):
            pass
        finally:
            sender.cancel()
            with contextlib.suppress(asyncio.CancelledError, Exception):
                await sender

    return Starlette(
        routes=[
            Route("/", index),
            Route("/api/layout", layout),
            Route("/api/scenario.{kind:str}", recording),
            Route("/api/save", save, methods=["POST"]),
            WebSocketRoute("/ws", stream),
            Mount("/static", StaticFiles(directory=STATIC), name="static"),
        ],
        middleware=[Middleware(Guard, served=served)],
    )


class Guard:
    """ASGI middleware: refuse (403) a request whose ``Host`` is not an address served (a DNS-rebinding page names
    its own), and a WebSocket or a ``POST`` whose ``Origin`` is another site's (a browser always sends one there)."""

    def __init__(self, app: Any, served: list[str]):
        self.app = app
        self.hosts = set(served)
        self.origins = {f"http://{h}" for h in served}

    async def __call__(self, scope: dict[str, Any], receive: Any, send: Any) -> None:
        if scope["type"] in ("http", "websocket"):
            refusal = self.refusal(scope)
            if refusal:
                await self.refuse(scope, receive, send, refusal)
                return
        await self.app(scope, receive, send)

    def refusal(self, scope: dict[str, Any]) -> str:
        """Why the request is refused ("" if it is not)."""
        headers = {k.decode("latin-1").lower(): v.decode("latin-1") for k, v in scope["headers"]}
        if headers.get("host") not in self.hosts:
            return f"this server answers to {' or '.join(sorted(self.hosts))} only, not {headers.get('host')!r}"
        origin = headers.get("origin")
        writes = scope["type"] == "websocket" or scope.get("method") not in ("GET", "HEAD")
        if writes and origin is not None and origin not in self.origins:
            return f"the live session takes commands from its own page only, not from {origin!r}"
        return ""

    @staticmethod
    async def refuse(scope: dict[str, Any], receive: Any, send: Any, why: str) -> None:
        from starlette.responses import PlainTextResponse

        if scope["type"] == "websocket":
            await receive()  # the connect message; closing before accepting answers the handshake 403
            await send({"type": "websocket.close", "code": 1008, "reason": why[:120]})
            return
        await PlainTextResponse(why, status_code=403)(scope, receive, send)


class LivePanel:
    """A served live session: :attr:`url` to open, :attr:`session` and :attr:`runner` to drive it, :meth:`stop`.

    In a notebook the handle shows the page inline (an IFrame).
    """

    def __init__(self, runner: Runner, host: str = "127.0.0.1", port: int = 0):
        require_server()
        import uvicorn

        self.runner = runner
        self.session: LiveSession = runner.session
        self._socket = socket.socket(socket.AF_INET, socket.SOCK_STREAM)
        if os.name != "nt":  # on Windows the option would let two servers share the port
            self._socket.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
        try:
            self._socket.bind((host, port))
        except OSError as exc:
            self._socket.close()
            reason = f"cannot serve the live panel on {host}:{port} ({exc.strerror})"
            raise PlcError(f"{reason}; try another --port (0: any free one)") from None
        self._socket.listen(64)  # connections wait in the backlog until the server accepts them
        self.host, self.port = host, self._socket.getsockname()[1]
        self.token = secrets.token_urlsafe(32)
        """The session's token: the page gets it when it loads; a WebSocket or a write without it is refused."""
        served = [f"{name}:{self.port}" for name in dict.fromkeys((*LOCAL_NAMES, host))]
        config = uvicorn.Config(make_app(runner, self.token, served), log_level="warning", lifespan="off", ws="auto")
        self._server = uvicorn.Server(config)
        self._thread = threading.Thread(target=self._server.run, kwargs={"sockets": [self._socket]}, daemon=True)
        self._thread.start()
        for _ in range(200):  # the server is up within a moment; a page opened before then would wait anyway
            if self._server.started or not self._thread.is_alive():
                break
            time.sleep(0.05)
        runner.start()

    @property
    def url(self) -> str:
        return f"http://{self.host}:{self.port}/"

    def stop(self) -> None:
        """Stop the simulation's thread and the server (the session stays, to be saved or graded)."""
        self.runner.stop()
        self._server.should_exit = True
        self._thread.join(timeout=5)
        self._socket.close()

    def _repr_html_(self) -> str:
        return f'<iframe src="{self.url}" width="100%" height="720" style="border:1px solid #ccc"></iframe>'

    def __repr__(self) -> str:
        return f"<LivePanel {self.session.target.name} at {self.url}>"


def open_live(
    target: str,
    program: str | Path,
    *,
    scenario: str | None = None,
    seed: int = 1,
    port: int = 0,
    speed: float | None = 1.0,
    paused: bool = False,
    save_scenario: str | Path | None = None,
) -> LivePanel:
    """Serve a live session of ``program`` on ``target`` and return its handle (``.url``; in a notebook the
    handle shows the page). ``port=0`` picks a free port; ``speed=None`` runs as fast as possible."""
    runner = Runner(LiveSession(target, program, scenario=scenario, seed=seed), speed=speed, paused=paused)
    runner.save_path = str(save_scenario) if save_scenario else None
    return LivePanel(runner, port=port)
