"""What the PLC836 mechanism exercises P-01 and P-02 share: the SPINDLE rig's I/O table and their programs'
folder (``exercises/solutions/P_NN/``, ``.mech`` files in the chapter's text and ``.py`` in the Python form)."""

from __future__ import annotations

from typing import Any

from exercises._common import solution
from plants import Spindle
from plcsim.exercise import IO, Solution


def mech_solution(number: str, name: str, *args: Any, **kwargs: Any) -> Solution:
    """A shipped program in the chapter's text: ``exercises/solutions/P_01/<name>.mech``."""
    return solution(number, name, *args, suffix=".mech", **kwargs)


def spindle_io(button: str, gloss: str, *lamps: IO) -> list[IO]:
    """The spindle's I/O table with one push-button (``REV`` or ``START``), the error cell BZH11 and ``lamps``."""
    return [
        *lamps,
        IO(button, gloss, "Bool", "%I0.0", "NO"),
        IO("KSMP", "auxiliary contact of the motor-positive contactor (closed: TRUE)", "Bool", "%I0.1", "NO"),
        IO("KSMN", "auxiliary contact of the motor-negative contactor", "Bool", "%I0.2", "NO"),
        IO("SMP", "motor-positive contactor (spindle clockwise)", "Bool", "%Q0.0"),
        IO("SMN", "motor-negative contactor (spindle counter-clockwise)", "Bool", "%Q0.1"),
        IO("BZH11", "error cell: the number of the last error (4.NN)", "Int", "%MW10", comment="the chapter's BZH11"),
    ]


def spindle() -> Spindle:
    return Spindle()
