"""Fast readers of many symbols at once: one generated function per set, built when a program loads.

The controller reads its symbols at every cycle's end (the outputs, the values the trace records) and its
input symbols whenever a terminal changed; one call returning a tuple is several times cheaper than a
loop over operands. The function is generated from the operands' numbers only (never program text).

>>> from plcsim.tecomat.memory import Scratchpad, parse_address
>>> pad = Scratchpad.sized(x=4, y=4, s=4, r=4)
>>> pad.areas["R"][0:2] = bytes([0x34, 0x12]); pad.areas["Y"][1] = 0b100
>>> read = reader(pad, [parse_address("RW0"), parse_address("Y1.2"), parse_address("R1")])
>>> read()
(4660, True, 18)
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from functools import partial
from typing import Any

from plcsim.tecomat.memory import Operand, Scratchpad


def reader(pad: Scratchpad, operands: Sequence[Operand]) -> Callable[[], tuple[Any, ...]]:
    """A function returning the operands' values (bits as bools, bytes and words as ints) as a tuple."""
    areas = sorted({op.area for op in operands})
    exprs = []
    for op in operands:
        a = f"a{op.area}"
        if op.width == "bit":
            exprs.append(f"{a}[{op.index}] >> {op.bit} & 1 == 1")
        elif op.width == "byte":
            exprs.append(f"{a}[{op.index}]")
        else:
            exprs.append(f"({a}[{op.index}] | {a}[{op.index + 1}] << 8)")
    params = ", ".join(f"a{area}" for area in areas)
    body = "".join(f"{e}, " for e in exprs)
    fn = eval(f"lambda {params}: ({body})", {"__builtins__": {}})  # generated from numbers, not program text
    return partial(fn, *(pad.areas[area] for area in areas))
