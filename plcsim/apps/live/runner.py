"""Pacing a live session to the wall clock, and the page's commands: the one place that reads the clock.

A :class:`Runner` owns a :class:`~plcsim.apps.live.session.LiveSession` and a thread. Every frame (20 ms of wall time)
it advances the simulation by the wall time passed × the speed (×0.1 … ×10), or as far as 20 ms of computing allows
("as fast as possible"), and takes a snapshot of the state for the page. The page's commands (a press, a pause, a
speed) run under the same lock, between two chunks, so each one lands on a step boundary. The wall clock decides
only *how far* each chunk goes; the session's trace depends on the actions and their instants alone.
"""

from __future__ import annotations

import threading
import time
from collections.abc import Callable
from typing import Any

from plcsim.apps.live.session import LiveSession
from plcsim.core.errors import PlcError

FRAME_S = 0.02
"""Wall time between two chunks (50 per second); the page is sent at most every other one."""
SPEEDS = (0.1, 0.2, 0.5, 1.0, 2.0, 5.0, 10.0)
"""The paces the page offers (simulated seconds per wall second), besides "as fast as possible"."""
MAX_LAG_S = 0.25
"""Wall time a slow simulation may owe before the runner gives up catching up (it then runs as fast as it can)."""


class Runner:
    """Run ``session`` on a thread at ``speed``; :meth:`command` takes the page's commands."""

    def __init__(self, session: LiveSession, *, speed: float | None = 1.0, paused: bool = False):
        self.session = session
        self.lock = threading.RLock()
        self.speed = speed  # None: as fast as possible
        self.paused = paused
        self.actual_speed = 0.0
        self.snapshot: dict[str, Any] = {}
        self.version = 0
        self.finished = threading.Event()
        self._stop = threading.Event()
        self._thread: threading.Thread | None = None
        self._owed_ns = 0.0
        self._take_snapshot()

    # -- the thread -----------------------------------------------------------------------------------

    def start(self) -> None:
        self._thread = threading.Thread(target=self._loop, name="plcsim-live", daemon=True)
        self._thread.start()

    def stop(self) -> None:
        """Stop the thread (the session stays as it is, ready to be saved)."""
        self._stop.set()
        if self._thread is not None:
            self._thread.join(timeout=5)

    def _loop(self) -> None:
        last = time.perf_counter()
        while not self._stop.wait(FRAME_S):
            now = time.perf_counter()
            wall, last = now - last, now
            with self.lock:
                t0 = self.session.now
                try:
                    self.tick(wall, deadline=now + FRAME_S)
                except Exception as exc:  # noqa: BLE001 - a bug of ours: the page says so instead of freezing
                    self.session.error = f"the live session failed: {type(exc).__name__}: {exc}"
                self.actual_speed = (self.session.now - t0) / 1e9 / wall if wall > 0 else 0.0
                self._take_snapshot()

    def tick(self, wall_s: float, deadline: float | None = None) -> None:
        """Advance by ``wall_s`` × speed (as fast as possible: until ``deadline`` on :func:`time.perf_counter`)."""
        if self.paused or self.session.error is not None:
            self._owed_ns = 0.0
            return
        stop = (lambda: time.perf_counter() > deadline) if deadline is not None else None
        if self.speed is None:
            self.session.advance(1 << 62, stop=stop)
            return
        self._owed_ns = min(self._owed_ns + wall_s * self.speed * 1e9, MAX_LAG_S * self.speed * 1e9)
        t0 = self.session.now
        if self._owed_ns >= self.session.sim.dt_ns:
            self.session.advance(int(self._owed_ns), stop=stop)
        self._owed_ns -= self.session.now - t0

    def _take_snapshot(self) -> None:
        state = self.session.state()
        state.update(paused=self.paused, speed=self.speed, actual_speed=round(self.actual_speed, 3))
        self.snapshot = state
        self.version += 1

    # -- the page's commands --------------------------------------------------------------------------

    def command(self, message: Any) -> dict[str, Any] | None:
        """Carry out one command from the page; returns a reply for it (or None), an error as ``{"type":
        "error"}``. Commands: ``do`` (verb, target, args), ``release``, ``toggle``, ``write`` (tag, text, force),
        ``pause``, ``resume``, ``scan``, ``speed`` (value or null), ``grade``, ``save``, ``digest``, ``end``."""
        if not isinstance(message, dict) or not isinstance(message.get("args", {}), dict):
            return {"type": "error", "message": f"a command is an object such as {{'op': 'pause'}}, not {message!r}"}
        op = message.get("op")
        handler: Callable[[dict[str, Any]], dict[str, Any] | None] | None = getattr(self, f"_op_{op}", None)
        if handler is None:
            return {"type": "error", "message": f"unknown command {op!r}"}
        with self.lock:
            try:
                reply = handler(message)
            except (PlcError, KeyError, ValueError, TypeError) as exc:
                reply = {"type": "error", "message": str(exc.args[0] if isinstance(exc, KeyError) else exc)}
            self._take_snapshot()
        return reply

    def _op_do(self, m: dict[str, Any]) -> None:
        self.session.do(m["verb"], m.get("target", ""), **m.get("args", {}))

    def _op_release(self, m: dict[str, Any]) -> None:
        self.session.release(m["target"])

    def _op_toggle(self, m: dict[str, Any]) -> None:
        self.session.toggle(m["target"])

    def _op_write(self, m: dict[str, Any]) -> None:
        self.session.write_text(m["target"], str(m["text"]), forced=bool(m.get("force")))

    def _op_pause(self, _m: dict[str, Any]) -> None:
        self.paused = True

    def _op_resume(self, _m: dict[str, Any]) -> None:
        self.paused = False

    def _op_scan(self, _m: dict[str, Any]) -> None:
        self.paused = True
        self.session.scan()

    def _op_speed(self, m: dict[str, Any]) -> None:
        value = m.get("value")
        if value is not None and not 0.01 <= float(value) <= 100:
            raise ValueError(f"speed {value} is outside ×0.01 … ×100")
        self.speed = None if value is None else float(value)
        self._owed_ns = 0.0

    def _op_digest(self, _m: dict[str, Any]) -> dict[str, Any]:
        return {"type": "digest", "t_ns": self.session.now, "digest": self.session.sim.trace.digest()}

    def _op_grade(self, _m: dict[str, Any]) -> dict[str, Any]:
        results = [
            {"title": check.title, "passed": verdict.passed, "message": verdict.message}
            for check, verdict in self.session.grade()
        ]
        return {"type": "graded", "t_ns": self.session.now, "results": results}

    def _op_save(self, _m: dict[str, Any]) -> dict[str, Any]:
        return {"type": "saved", **self.save()}

    def _op_end(self, _m: dict[str, Any]) -> dict[str, Any]:
        self.paused = True
        reply = {"type": "ended", **self.save()}
        self.finished.set()
        return reply

    # -- the record --------------------------------------------------------------------------------------

    save_path: str | None = None
    """Where ``save`` writes the scenario (None: nowhere; the page downloads it)."""

    def save(self) -> dict[str, Any]:
        """The recording so far as TOML and Python, written to :attr:`save_path` if set, with the trace digest."""
        with self.lock:
            rec = self.session.recording()
            written = str(rec.save(self.save_path)) if self.save_path else None
            return {
                "path": written,
                "t_ns": self.session.now,
                "digest": self.session.sim.trace.digest(),
                "toml": rec.to_toml(),
                "python": rec.to_python(),
                "actions": len(rec.actions),
            }
