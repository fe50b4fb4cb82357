"""The grading child: ``python -m plcsim.grading.sandbox.child REQUEST``, started by the grader
(:mod:`plcsim.grading.sandbox.parent`).

It confines itself (:mod:`plcsim.grading.sandbox.confine`), loads the exercise and the submission, runs every
scenario (:mod:`plcsim.grading.run`; it imports nothing of the grader) and writes the raw results
(:mod:`plcsim.grading.run_result`) to the file descriptor the grader passed; then it exits. It sends no
score: the grader evaluates the checks itself.

On the portable path (``"confine": false`` in the request: Windows, or ``PLCSIM_SANDBOX=portable``)
it applies none of that and writes its result to a file; the grader watches it from outside
(:mod:`plcsim.grading.sandbox.watchdog`), and it ends itself when the grader's end of its stdin closes.

With a PID namespace, the process the grader started forks once: the fork is process 1 of the
namespace and does the work, the first waits for it and exits with its status (a death by signal
N as exit code 128 + N), so that the grader can tell a CPU-time limit from a crash.
"""

from __future__ import annotations

import importlib
import json
import os
import sys
from collections.abc import Callable
from typing import Any

from plcsim.grading.sandbox.exits import MEMORY_EXIT, SIGNAL_EXIT_BASE


def main(argv: list[str], work: Callable[[dict[str, Any]], bytes] | None = None) -> int:
    """Confine this process, do ``work`` (default: grade the request) and send its message."""
    from plcsim.grading.sandbox import confine

    request = json.loads(argv[1])
    fd = request["fd"]
    limits = request["limits"]
    if request.get("confine", True):
        confine.set_limits(limits["cpu_seconds"], limits["memory_mb"])
        if confine.enter_namespaces()[0]:
            pid = os.fork()
            if pid:
                if fd is not None:
                    os.close(fd)
                return _exit_code(os.waitpid(pid, 0)[1])
            confine.die_with_parent()
    else:
        confine.exit_with_grader()
    try:
        message = (work or grade_request)(request)
    except MemoryError as exc:
        if not exc.args:  # the allocator's: out of memory, perhaps too far to build even a message
            return MEMORY_EXIT
        message = _raised_memory_error(exc)
    if fd is None:  # the portable path (Windows): a file in scratch
        with open(request["result_file"], "wb") as f:
            f.write(message)
        return 0
    _write_all(fd, message)
    os.close(fd)
    return 0


def lock_down(request: dict[str, Any]) -> list[str]:
    """The confinement applied once the exercise is loaded: no new process, reads only of what the
    grader lists (the submission, the Python installation and packages), writes only in scratch."""
    from plcsim.grading.sandbox import confine

    if not request.get("confine", True):
        return ["portable path: no confinement"]
    return confine.forbid_processes(request.get("cgroup")) + confine.restrict_files(
        request["scratch"], request["readable"]
    )


def grade_request(request: dict[str, Any]) -> bytes:
    """Load the exercise, lock down, run the submission in every scenario: the message for the grader."""
    from plcsim.core.errors import ExerciseError, PlcError
    from plcsim.frontends import read_program
    from plcsim.grading.run import load_error_kind, run_scenarios
    from plcsim.grading.run_result import encode_failure, encode_runs

    exercise = getattr(importlib.import_module(request["module"]), request["attribute"])
    lock_down(request)
    try:
        program = read_program(request["path"])
        runs, _ = run_scenarios(
            exercise, program, seed=request["seed"], scenarios=request["scenarios"], geometry=request["geometry"]
        )
        return encode_runs(runs, geometry=request["geometry"])
    except ExerciseError as exc:  # a scenario the exercise cannot run: the instructor's mistake, voids the grade
        return encode_failure("grader error", str(exc))
    except PlcError as exc:  # the grader ran the exercise with a probe program: the fault is this program's
        kind = load_error_kind(exc)
        return encode_failure("program error" if kind == "grader error" else kind, str(exc))
    except MemoryError as exc:
        if exc.args:
            return _raised_memory_error(exc)
        limit = request["limits"]["memory_mb"]
        return encode_failure("memory limit", f"the submission ran out of memory (the limit is {limit} MB)")
    except RecursionError as exc:
        return encode_failure("program error", f"{request['path']}: the program nests too deeply ({exc})")
    except ImportError as exc:  # a submission can neither import nor raise: the grader's installation is at fault
        return encode_failure(
            "grader error",
            f"the grading child could not import {exc.name or 'a module'} ({exc}): the grader's installation is "
            f"incomplete or not readable by the child; the submission was not graded",
        )
    except Exception as exc:  # noqa: BLE001 - the grader reports it as a crash of the child
        return encode_failure("crash", f"the grading child failed: {type(exc).__name__}: {exc}")


def _raised_memory_error(exc: MemoryError) -> bytes:
    """A MemoryError with a message was raised by code, not by the allocator: not a memory limit."""
    from plcsim.grading.run_result import encode_failure

    return encode_failure("program error", f"the program raised MemoryError({str(exc)[:200]!r}); memory was not short")


def _exit_code(status: int) -> int:
    if os.WIFSIGNALED(status):
        return SIGNAL_EXIT_BASE + os.WTERMSIG(status)
    return os.WEXITSTATUS(status) if os.WIFEXITED(status) else 1


def _write_all(fd: int, data: bytes) -> None:
    view = memoryview(data)
    while view:
        view = view[os.write(fd, view) :]


if __name__ == "__main__":
    sys.exit(main(sys.argv))
