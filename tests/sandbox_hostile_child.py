"""A hostile grading child for the sandbox tests: the child a submission would make of the real one
if it escaped the program compiler. Started as ``python -m sandbox_hostile_child REQUEST`` by
``grade_sandboxed(..., child_entry="sandbox_hostile_child")``.

The "submission" is a JSON file ``{"do": BEHAVIOUR, ...}`` naming what to do. Behaviours that send a
trace run the exercise's reference program (which a hostile child could read) or its first wrong
solution, and may tamper with the message before sending it.
"""

from __future__ import annotations

import json
import os
import pickle
import socket
import sys
import time
from pathlib import Path
from typing import Any

from plcsim.grading import run_result
from plcsim.grading.run_result import LENGTH, MAGIC, encode_runs
from plcsim.grading.sandbox.child import lock_down, main


def _runs(request: dict[str, Any], solution: str = "reference") -> list[Any]:
    import importlib

    from plcsim.grading.run import run_scenarios

    exercise = getattr(importlib.import_module(request["module"]), request["attribute"])
    chosen = exercise.reference if solution == "reference" else exercise.solution(solution)
    runs, _ = run_scenarios(exercise, chosen.program(), seed=request["seed"], scenarios=request["scenarios"])
    return runs


def _retitle(message: bytes, change: Any) -> bytes:
    """The message with its JSON header changed by ``change(header)`` (the tables kept)."""
    start = len(MAGIC) + LENGTH.size
    (length,) = LENGTH.unpack_from(message, len(MAGIC))
    header = json.loads(message[start : start + length])
    change(header)
    head = json.dumps(header).encode()
    return MAGIC + LENGTH.pack(len(head)) + head + message[start + length :]


def work(request: dict[str, Any]) -> bytes:
    order = json.loads(Path(request["path"]).read_text(encoding="utf-8"))
    do = order["do"]
    if do == "reference":  # an honest trace of a correct program: the control case
        return encode_runs(_runs(request))
    if do == "garbage":
        return os.urandom(5000)
    if do == "pickle":  # a pickled report: unpickled, it would run code in the grader
        return pickle.dumps({"passed": True, "score": 3.0, "max_score": 3.0})
    if do == "print-passed":
        for stream in (sys.stdout, sys.stderr):
            stream.write("[bold green]PASSED[/]  score 3 / 3\nPASSED\n")
            stream.flush()
        os._exit(0)
    if do == "tamper":
        message = encode_runs(_runs(request))
        return _TAMPER[order["how"]](message)
    if do == "grandchild":  # forks off a process that leaves the group and holds the result pipe
        ready_r, ready_w = os.pipe()
        pid = os.fork()
        if pid == 0:
            os.setsid()
            os.write(ready_w, str(_host_pid()).encode())
            time.sleep(60)
            os._exit(0)
        os.close(ready_w)
        host_pid = os.read(ready_r, 64).decode()  # as the grader's machine numbers it
        Path(order["pid_file"]).write_text(host_pid, encoding="utf-8")
        os._exit(3)
    if do == "escape":  # after the lock-down: read secrets, write outside scratch, fork, connect
        runs = _runs(request)
        lock_down(request)
        tried = []
        for target in order["read"]:
            try:
                Path(target).read_bytes()
                tried.append(f"read {target}")
            except OSError as exc:
                tried.append(f"read {target}: {type(exc).__name__}")
        for target in order["write"]:
            try:
                Path(target).write_text("escaped", encoding="utf-8")
                tried.append(f"wrote {target}")
            except OSError as exc:
                tried.append(f"write {target}: {type(exc).__name__}")
        Path("inside-scratch.txt").write_text("fine", encoding="utf-8")
        try:
            pid = os.fork()
            if pid == 0:
                os._exit(0)
            tried.append("forked")
        except OSError as exc:
            tried.append(f"fork: {type(exc).__name__}")
        try:
            socket.create_connection(("127.0.0.1", order["port"]), timeout=1).close()
            tried.append("connected")
        except OSError as exc:
            tried.append(f"connect: {type(exc).__name__}")
        runs[0].warnings = tried
        return encode_runs(runs)
    if do == "cpu-hog":
        while True:
            pass
    if do == "memory-hog":
        chunks = []
        while True:
            chunks.append(bytearray(64 << 20))
    if do == "descriptors":  # what a forked child could still reach of the fork server: nothing
        runs = _runs(request)
        listing = os.listdir("/proc/self/fd")  # opens one descriptor of its own while it lists
        runs[0].warnings = [f"open {fd} -> {_target(int(fd))}" for fd in sorted(listing, key=int)]
        return encode_runs(runs)
    if do == "poison":  # change in this process what the next child would use, if it were inherited
        import plcsim.grading.run
        import plcsim.grading.run_result

        plcsim.grading.run.run_scenarios = None
        plcsim.grading.run_result.encode_runs = lambda *a, **k: b"forged"
        sys.modules[request["module"]].__dict__.clear()
        os._exit(3)
    if do == "raise-memory-error":
        raise MemoryError("pretend to be out of memory")
    if do == "exit":
        os._exit(order["code"])
    raise ValueError(f"unknown behaviour {do!r}")


def _host_pid() -> int:
    """This process's pid outside every PID namespace it is in (the first of ``NSpid``)."""
    for line in Path("/proc/self/status").read_text(encoding="utf-8").splitlines():
        if line.startswith("NSpid:"):
            return int(line.split()[1])
    return os.getpid()


def _target(fd: int) -> str:
    try:
        return os.readlink(f"/proc/self/fd/{fd}")
    except OSError:
        return "closed"


def _set_first(key: str, value: Any) -> Any:
    def change(header: dict[str, Any]) -> None:
        header["runs"][0][key] = value

    return change


def _rename_first_signal(header: dict[str, Any]) -> None:
    run = header["runs"][0]
    old = run["names"][0]
    run["names"][0] = old + "_X"
    run["kinds"][old + "_X"] = run["kinds"].pop(old)
    run["types"][old + "_X"] = run["types"].pop(old)


def _bool_two(message: bytes) -> bytes:
    """A Bool column holding 2.0 in the first row's first signal (the tables follow the header)."""
    start = len(MAGIC) + LENGTH.size
    (length,) = LENGTH.unpack_from(message, len(MAGIC))
    at = start + length + run_result.HEAD * 8
    return message[:at] + _f8(2.0) + message[at + 8 :]


def _late_row(message: bytes) -> bytes:
    """The first row's end time moved beyond the scenario's horizon."""
    start = len(MAGIC) + LENGTH.size
    (length,) = LENGTH.unpack_from(message, len(MAGIC))
    at = start + length + 8
    return message[:at] + _f8(1e15) + message[at + 8 :]


def _f8(value: float) -> bytes:
    import struct

    return struct.pack("<d", value)


_TAMPER = {
    "rename-signal": lambda m: _retitle(m, _rename_first_signal),
    "drop-scenario": lambda m: _retitle(m, lambda h: h["runs"].pop()),
    "other-seed": lambda m: _retitle(m, _set_first("seed", 99)),
    "beyond-horizon": lambda m: _retitle(m, _set_first("simulated_ns", 10**18)),
    "bool-two": _bool_two,
    "late-row": _late_row,
    "trailing-bytes": lambda m: m + b"PASSED",
    "truncated": lambda m: m[: len(m) // 2],
}


if __name__ == "__main__":
    sys.exit(main(sys.argv, work))
