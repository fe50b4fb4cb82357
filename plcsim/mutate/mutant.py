"""What every language's mutation operators share: the mutant they derive and the preset step they move a
number by. The bottom of :mod:`plcsim.mutate`: the operators (:mod:`plcsim.mutate.python`,
:mod:`plcsim.mutate.il`) import it, and the engine that grades their mutants imports them.

A preset step is one unit in the decimal place below the value's leading digit, at least one
unit of the literal (10 s -> 9 s / 11 s, 3 s -> 2.9 s / 3.1 s, 100 ms -> 90 ms / 110 ms, PV 3 -> 2 / 4):
about a tenth of the preset, the size of slip that a check's tolerance should not absorb.

>>> preset_steps("10s"), preset_steps("3s"), preset_steps(3), preset_steps(True)
(['9s', '11s'], ['2900ms', '3100ms'], [2, 4], [])
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

from plcsim.core.errors import PlcError
from plcsim.core.literals import time_ms


@dataclass(frozen=True)
class Mutant:
    """One mutant of a program: what changed, where, and the mutated source."""

    number: int
    operator: str
    line: int
    description: str
    source: str

    def __str__(self) -> str:
        return f"line {self.line}: {self.description}"


def preset_steps(value: Any) -> list[Any]:
    """The preset one step below and above ``value`` (see the module docstring)."""
    if isinstance(value, bool):
        return []
    if isinstance(value, int):
        step = max(1, _tenth_of_magnitude(abs(value)))
        return [v for v in (value - step, value + step) if v >= 0 or value < 0]
    if isinstance(value, str):
        try:
            ms = time_ms(value)
        except PlcError:
            return []
        step = max(1, _tenth_of_magnitude(ms))
        return [_time_literal(v) for v in (ms - step, ms + step) if v >= 0]
    return []


def _tenth_of_magnitude(n: int) -> int:
    return 10 ** (int(math.log10(n)) - 1) if n >= 10 else 0


def _time_literal(ms: int) -> str:
    return f"{ms // 1000}s" if ms % 1000 == 0 and ms else f"{ms}ms"


__all__ = ["Mutant", "preset_steps"]
