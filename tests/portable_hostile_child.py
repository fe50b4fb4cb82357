"""More hostile grading children for the portable path (``tests/grading/test_portable_sandbox.py``), on top of
those of ``tests/sandbox_hostile_child.py``: what a child the grader cannot confine may do to it.

The "submission" is a JSON file ``{"do": BEHAVIOUR, ...}``.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
import time
from pathlib import Path
from typing import Any

from sandbox_hostile_child import _runs
from sandbox_hostile_child import work as hostile_work

from plcsim.grading.run_result import encode_runs
from plcsim.grading.sandbox.child import main


def work(request: dict[str, Any]) -> bytes:
    order = json.loads(Path(request["path"]).read_text(encoding="utf-8"))
    do = order["do"]
    if do == "huge-result":  # the result file grows without end
        with open(request["result_file"], "wb") as f:
            while True:
                f.write(bytes(1 << 20))
    if do == "huge-stdout":  # floods its stdout, then sends an honest result
        for _ in range(order["megabytes"]):
            sys.stdout.write("PASSED " * 150_000)
        return encode_runs(_runs(request))
    if do == "spawn-then-hog":  # starts a process of its own, then loops
        sleeper = subprocess.Popen([sys.executable, "-c", "import time; time.sleep(120)"])
        Path(order["pid_file"]).write_text(str(sleeper.pid), encoding="utf-8")
        while True:
            pass
    if do == "spawn-a-hog-then-sleep":  # the CPU time is spent by the process it starts, not by itself
        hog = subprocess.Popen([sys.executable, "-c", "while True: pass"])
        Path(order["pid_file"]).write_text(str(hog.pid), encoding="utf-8")
        time.sleep(120)
    if do == "tell-pid-then-hog":
        Path(order["pid_file"]).write_text(str(os.getpid()), encoding="utf-8")
        while True:
            pass
    return hostile_work(request)


if __name__ == "__main__":
    sys.exit(main(sys.argv, work))
