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
>>> values = {}
>>> storer(pad, ["W", "B"], [parse_address("RW0"), parse_address("Y1.2")])(values); values
{'W': 4660, 'B': True}
>>> loader(pad, "R", ["L"], [parse_address("R2.1")])({"L": True}); pad.areas["R"][2]
2
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from functools import partial
from typing import Any

from plcsim.tecomat.memory import Operand, Scratchpad


def reader(pad: Scratchpad, operands: Sequence[Operand]) -> Callable[[], tuple[Any, ...]]:
    """A function returning the operands' values (bits as bools, bytes and words as ints) as a tuple."""
    areas = sorted({op.area for op in operands})
    params = ", ".join(f"a{area}" for area in areas)
    body = "".join(f"{_expr(op)}, " for op in operands)
    fn = eval(f"lambda {params}: ({body})", {"__builtins__": {}})  # generated from numbers, not program text
    return partial(fn, *(pad.areas[area] for area in areas))


def storer(pad: Scratchpad, names: Sequence[str], operands: Sequence[Operand]) -> Callable[[dict[str, Any]], None]:
    """A function storing the operands' values into a dict under their names (the traced symbols)."""
    areas = sorted({op.area for op in operands}) or ["R"]
    lines = [f"d[{name!r}] = {_expr(op)}" for name, op in zip(names, operands, strict=True)]
    source = _function("d, " + ", ".join(f"a{area}" for area in areas), lines)
    return partial(_compile(source), **{f"a{area}": pad.areas[area] for area in areas})


def loader(pad: Scratchpad, area: str, names: Sequence[str], operands: Sequence[Operand]) -> Callable[[dict], None]:
    """A function writing the values of a dict's names into their operands of ``area`` (the input terminals)."""
    lines = []
    for name, op in zip(names, operands, strict=True):
        a, i = f"a{area}", op.index
        if op.width == "bit":
            lines.append(f"{a}[{i}] = {a}[{i}] | {1 << op.bit} if d[{name!r}] else {a}[{i}] & {~(1 << op.bit) & 0xFF}")
        elif op.width == "byte":
            lines.append(f"{a}[{i}] = int(d[{name!r}]) & 255")
        else:
            lines += [f"v = int(d[{name!r}]) & 65535", f"{a}[{i}] = v & 255", f"{a}[{i + 1}] = v >> 8"]
    return partial(_compile(_function(f"d, a{area}", lines)), **{f"a{area}": pad.areas[area]})


def _expr(op: Operand) -> str:
    a = f"a{op.area}"
    if op.width == "bit":
        return f"{a}[{op.index}] >> {op.bit} & 1 == 1"
    if op.width == "byte":
        return f"{a}[{op.index}]"
    return f"({a}[{op.index}] | {a}[{op.index + 1}] << 8)"


def _function(params: str, lines: list[str]) -> str:
    return f"def f({params}):\n" + "".join(f"    {line}\n" for line in lines or ["pass"])


def _compile(source: str) -> Callable[..., Any]:
    namespace: dict[str, Any] = {}
    exec(source, {"__builtins__": {"int": int}}, namespace)  # generated from numbers and quoted names
    return namespace["f"]


def overlapping(operands: Sequence[Operand]) -> bool:
    """Whether two operands share a bit (two input names on one terminal)."""
    seen: set[tuple[int, int]] = set()
    for op in operands:
        if op.width == "bit":
            bits = {(op.index, op.bit)}
        else:
            size = 2 if op.width == "word" else 1
            bits = {(op.index + k, b) for k in range(size) for b in range(8)}
        if seen & bits:
            return True
        seen |= bits
    return False
