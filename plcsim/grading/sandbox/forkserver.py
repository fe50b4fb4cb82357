"""A fork server for the grading children (Linux): a trusted interpreter that has imported the grader's
modules once forks each child, instead of a fresh interpreter importing numpy, pymunk, plcsim and the
exercises again for every submission (0.5–0.7 s of CPU each, as much as grading a small exercise).

The server (``python -m plcsim.grading.sandbox.forkserver FD``, started by the grader with the children's environment)
never runs submission code. For each request it imports the modules the request names (the exercise's
and the child's entry module: trusted code the grader imports itself), forks, and later reports the
child's exit status and CPU time. The forked child closes every descriptor but its result pipe (so it
cannot reach the server's socket), starts its own session, names itself ``plcsim-grade``, takes its
scratch folder, environment and temporary folder from the request and runs the entry module as
``python -m`` would. From there on it is the child a fresh interpreter would have been: it confines
itself before it loads the submission (:mod:`plcsim.grading.sandbox.child`). Nothing one child does reaches
another: each is forked from the server, in which no submission ever ran.

The grader's side is :class:`ForkServer`; :func:`shared` gives the process's server for an
environment, starting it (again) when needed. ``PLCSIM_FORKSERVER=off`` starts every child afresh.
"""

from __future__ import annotations

import contextlib
import importlib
import json
import os
import runpy
import select
import signal
import socket
import subprocess
import sys
import tempfile
import threading
from collections.abc import Mapping
from typing import Any

VARIABLE = "PLCSIM_FORKSERVER"
"""``PLCSIM_FORKSERVER=off`` starts every grading child as a fresh interpreter."""
MAX_MESSAGE = 1 << 16
"""The largest request the server reads (a request is a few kB: paths and limits)."""
CHILD_NAME = b"plcsim-grade"
"""The name (``/proc/PID/comm``) of a forked child and of what it starts without exec."""
_PR_SET_NAME = 15
_PR_SET_PDEATHSIG = 1


class ForkServerError(RuntimeError):
    """The server is gone or refused a request: the grader starts that child afresh instead."""


def enabled() -> bool:
    """True where children are forked from a server: Linux, unless ``PLCSIM_FORKSERVER=off``.

    (macOS is left out: forking a process that has loaded its system frameworks is unsafe there.)"""
    return sys.platform.startswith("linux") and os.environ.get(VARIABLE, "").strip().lower() not in ("off", "0")


class ForkServer:
    """The grader's handle on one server process: start children, learn when they end.

    Thread-safe: a batch grades from several threads. A reader thread receives the server's replies;
    once the server is gone every waiting call raises :class:`ForkServerError`."""

    def __init__(self, env: Mapping[str, str]) -> None:
        ours, theirs = socket.socketpair(socket.AF_UNIX, socket.SOCK_SEQPACKET)
        try:
            self.process = subprocess.Popen(
                [sys.executable, "-B", "-m", "plcsim.grading.sandbox.forkserver", str(theirs.fileno())],
                env=dict(env),
                cwd="/",
                stdin=subprocess.DEVNULL,
                stdout=subprocess.DEVNULL,
                stderr=subprocess.DEVNULL,
                pass_fds=(theirs.fileno(),),
                start_new_session=True,
            )
        except OSError:
            ours.close()
            raise
        finally:
            theirs.close()
        self._socket = ours
        self._send = threading.Lock()
        self._changed = threading.Condition()
        self._started: dict[int, int | str] = {}  # request id -> pid, or the server's refusal
        self._ended: dict[int, tuple[int, float]] = {}  # pid -> (wait status, CPU seconds)
        self._next_id = 0
        self.alive = True
        threading.Thread(target=self._receive, name="plcsim-forkserver", daemon=True).start()

    def spawn(self, entry: str, request: dict[str, Any], env: Mapping[str, str], cwd: str, fd: int) -> int:
        """Fork a child running ``python -m entry`` on ``request`` in ``cwd`` with ``env``; ``fd`` is its
        result pipe (the server gets a copy; the child's number for it replaces ``request["fd"]``)."""
        with self._send:
            self._next_id += 1
            ident = self._next_id
            fields = {"id": ident, "entry": entry, "request": request, "env": dict(env), "cwd": cwd}
            message = json.dumps(fields).encode("utf-8")
            if len(message) > MAX_MESSAGE:
                raise ForkServerError(f"the request has {len(message)} bytes, more than the server reads")
            try:
                socket.send_fds(self._socket, [message], [fd])
            except OSError as exc:
                self._gone()
                raise ForkServerError(f"the fork server is gone: {exc}") from None
        with self._changed:
            while ident not in self._started and self.alive:
                self._changed.wait()
            started = self._started.pop(ident, None)
        if not isinstance(started, int):
            raise ForkServerError(f"the fork server did not start the child: {started or 'it ended'}")
        return started

    def exited(self, pid: int) -> bool:
        """True once the child ``pid`` has ended (its status is kept for :meth:`reap`)."""
        with self._changed:
            if pid in self._ended:
                return True
            if not self.alive:
                raise ForkServerError("the fork server ended before its child")
            return False

    def reap(self, pid: int) -> tuple[int, float]:
        """Wait for the child (already killed): its exit code (negative: killed by that signal) and CPU seconds."""
        with self._changed:
            while pid not in self._ended:
                if not self.alive:
                    raise ForkServerError("the fork server ended before its child")
                self._changed.wait()
            status, cpu_s = self._ended.pop(pid)
        return os.waitstatus_to_exitcode(status), cpu_s

    def close(self) -> None:
        """End the server (it kills the children it still has) and wait for it."""
        self._gone()
        with contextlib.suppress(OSError):
            self._socket.shutdown(socket.SHUT_RDWR)
        try:
            self.process.wait(timeout=5)
        except subprocess.TimeoutExpired:
            self.process.kill()
            self.process.wait()

    def _receive(self) -> None:
        while True:
            try:
                data = self._socket.recv(MAX_MESSAGE)
            except OSError:
                data = b""
            if not data:
                self._gone()
                return
            reply = json.loads(data)
            with self._changed:
                if "id" in reply:
                    self._started[reply["id"]] = reply.get("pid") or reply.get("error", "no reason given")
                    self._ended.pop(reply.get("pid"), None)  # an unreaped child's end, with the pid reused
                else:
                    self._ended[reply["pid"]] = (reply["status"], reply["cpu_s"])
                self._changed.notify_all()

    def _gone(self) -> None:
        with self._changed:
            self.alive = False
            self._changed.notify_all()


_SERVERS: dict[tuple[tuple[str, str], ...], ForkServer] = {}
_SERVERS_LOCK = threading.Lock()


def shared(env: Mapping[str, str]) -> ForkServer:
    """This process's server for children with the environment ``env``, started if there is none alive."""
    key = tuple(sorted(env.items()))
    with _SERVERS_LOCK:
        server = _SERVERS.get(key)
        if server is None or not server.alive:
            server = _SERVERS[key] = ForkServer(env)
        return server


def _forget_servers_in_a_forked_grader() -> None:
    """In a child forked from the grader: drop the grader's servers (their reader threads did not come
    along, and a second process on one socket would take the other's replies); each is closed here only,
    so the server lives on for the grader, and this process starts its own when it grades."""
    global _SERVERS_LOCK
    _SERVERS_LOCK = threading.Lock()  # another thread may have held it at the fork
    servers = list(_SERVERS.values())
    _SERVERS.clear()
    for server in servers:
        server.alive = False
        with contextlib.suppress(OSError):
            server._socket.close()


if hasattr(os, "register_at_fork"):
    os.register_at_fork(after_in_child=_forget_servers_in_a_forked_grader)


def close_all() -> None:
    """End every server this process started (tests; a grader's servers also end with it)."""
    with _SERVERS_LOCK:
        servers = list(_SERVERS.values())
        _SERVERS.clear()
    for server in servers:
        server.close()


# -- the server ----------------------------------------------------------------------------------------


def serve(control: socket.socket) -> None:
    """Fork a child for each request on ``control``, report each child's end; return at end of file,
    killing the children still running (the grader is gone)."""
    wake_r, wake_w = os.pipe()
    os.set_blocking(wake_r, False)
    os.set_blocking(wake_w, False)
    signal.set_wakeup_fd(wake_w)
    signal.signal(signal.SIGCHLD, lambda signum, frame: None)
    children: set[int] = set()
    try:
        while True:
            ready, _, _ = select.select([control, wake_r], [], [])
            if wake_r in ready:
                with contextlib.suppress(BlockingIOError):
                    while os.read(wake_r, 4096):
                        pass
                _reap(control, children)
            if control in ready:
                try:
                    data, fds, _, _ = socket.recv_fds(control, MAX_MESSAGE, 1)
                except OSError:
                    return
                if not data:
                    return
                _start(control, data, fds, children)
    finally:
        for pid in children:
            with contextlib.suppress(OSError):
                os.killpg(pid, signal.SIGKILL)


def _start(control: socket.socket, data: bytes, fds: list[int], children: set[int]) -> None:
    request = json.loads(data)
    if len(fds) != 1:
        for fd in fds:
            os.close(fd)
        _reply(control, {"id": request.get("id"), "error": f"{len(fds)} descriptors sent with the request, not 1"})
        return
    for module in (request["entry"], request["request"].get("module")):
        if module:
            with contextlib.suppress(Exception):  # the child imports it again and reports what fails
                importlib.import_module(module)
    started_r, started_w = os.pipe()
    try:
        pid = os.fork()
    except OSError as exc:  # no process to spare: the grader starts this child afresh or reports it
        for fd in (started_r, started_w, fds[0]):
            os.close(fd)
        _reply(control, {"id": request["id"], "error": f"cannot fork: {exc}"})
        return
    if pid == 0:
        os.close(started_r)
        _become_child(request, fds[0], started_w)
    os.close(fds[0])
    os.close(started_w)
    os.read(started_r, 1)  # the child has its own session (or died): the grader may kill its group now
    os.close(started_r)
    children.add(pid)
    _reply(control, {"id": request["id"], "pid": pid})


def _reap(control: socket.socket, children: set[int]) -> None:
    while children:
        try:
            pid, status, usage = os.wait4(-1, os.WNOHANG)
        except ChildProcessError:
            return
        if pid == 0:
            return
        children.discard(pid)
        _reply(control, {"pid": pid, "status": status, "cpu_s": usage.ru_utime + usage.ru_stime})


def _reply(control: socket.socket, reply: dict[str, Any]) -> None:
    with contextlib.suppress(OSError):  # the grader is gone: the loop ends at end of file
        control.send(json.dumps(reply).encode("utf-8"))


def _become_child(message: dict[str, Any], fd: int, started: int) -> None:
    """In the forked child: shed the server (its socket, signal handling, folder, environment), then
    run the entry module as ``python -m`` does. Never returns.

    ``started`` is written once the child leads its own session, before the server names its pid: a
    grader killing the child's group right away must find the group."""
    code = 1
    try:
        os.setsid()
        os.write(started, b"s")
        signal.set_wakeup_fd(-1)
        signal.signal(signal.SIGCHLD, signal.SIG_DFL)
        os.closerange(3, fd)
        os.closerange(fd + 1, os.sysconf("SC_OPEN_MAX"))
        _name_and_tie_to_server()
        os.chdir(message["cwd"])
        os.environ.clear()
        os.environ.update(message["env"])
        tempfile.tempdir = None  # computed again from TMPDIR, the child's scratch
        request = {**message["request"], "fd": fd}
        sys.argv = [message["entry"], json.dumps(request)]
        runpy.run_module(message["entry"], run_name="__main__", alter_sys=True)
        code = 0
    except SystemExit as exc:
        code = exc.code if isinstance(exc.code, int) else (0 if exc.code is None else 1)
    except BaseException:  # noqa: BLE001 - a child that failed to start: the grader sees its exit code
        code = 1
    finally:
        os._exit(code)


def _name_and_tie_to_server() -> None:
    """``plcsim-grade`` in ``/proc/PID/comm`` (inherited by what the child forks), and a kill when the
    server ends (the grader killing the server ends every child it has)."""
    import ctypes

    libc = ctypes.CDLL(None, use_errno=True)
    libc.prctl(_PR_SET_NAME, ctypes.c_char_p(CHILD_NAME), 0, 0, 0)
    libc.prctl(_PR_SET_PDEATHSIG, signal.SIGKILL, 0, 0, 0)


def main(argv: list[str]) -> int:
    """``python -m plcsim.grading.sandbox.forkserver FD``: serve the requests on the socket ``FD`` until it closes."""
    control = socket.socket(fileno=int(argv[1]))
    import plcsim.grading.sandbox.child  # noqa: F401 - what every child imports, once for all
    from plcsim import frontends  # noqa: F401
    from plcsim.grading import run, run_result  # noqa: F401

    serve(control)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
