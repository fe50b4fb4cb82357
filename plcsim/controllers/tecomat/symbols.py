"""Fast readers of many symbols at once: one generated function per set, built when a program loads.

The controller reads its symbols at every cycle's end (the outputs, the values the trace records) and its
input symbols whenever a terminal changed; one call returning a tuple is several times cheaper than a
loop over operands. The function is generated from the operands' numbers only (never program text).

>>> from plcsim.controllers.tecomat.memory import Scratchpad, parse_address
>>> pad = Scratchpad.sized(x=4, y=4, s=4, r=4)
>>> pad.areas["R"][0:2] = bytes([0x34, 0x12]); pad.areas["Y"][1] = 0b100
>>> read = reader(pad, [parse_address("RW0"), parse_address("Y1.2"), parse_address("R1")])
>>> read()
(4660, True, 18)
>>> take, decode = snapshot(pad, [parse_address("RW0"), parse_address("Y1.2")])
>>> copies = take(); pad.areas["R"][0] = 0
>>> values = {}; decode(["W", "B"])(values, *copies); values
{'W': 4660, 'B': True}
>>> loader(pad, "R", [parse_address("R2.1"), parse_address("R2.3"), parse_address("R3")])((True, False, 7))
>>> pad.areas["R"][2:4].hex()
'0207'
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from functools import partial
from typing import Any

from plcsim.controllers.tecomat.memory import SIZE, Operand, Scratchpad


def reader(pad: Scratchpad, operands: Sequence[Operand]) -> Callable[[], tuple[Any, ...]]:
    """A function returning the operands' values (bits as bools, bytes and words as ints) as a tuple."""
    areas = sorted({op.area for op in operands})
    params = ", ".join(f"a{area}" for area in areas)
    body = "".join(f"{_expr(op)}, " for op in operands)
    fn = eval(f"lambda {params}: ({body})", {"__builtins__": {}})  # generated from numbers, not program text
    return partial(fn, *(pad.areas[area] for area in areas))


def snapshot(pad: Scratchpad, operands: Sequence[Operand]) -> tuple[Callable[[], tuple[bytearray, ...]], Any]:
    """``take()`` copying the registers the operands live in (a few short byte copies, at every cycle's end),
    and ``decode(names)`` making ``f(d, *copies)`` that stores the copied values into a dict by name (only
    when someone reads them: most cycles nobody does)."""
    areas = sorted({op.area for op in operands})
    ends = {a: max(op.index + SIZE[op.width] for op in operands if op.area == a) for a in areas}
    params = ", ".join(f"a{area}" for area in areas)
    copies = "".join(f"a{area}[:{ends[area]}], " for area in areas)
    take = eval(f"lambda {params}: lambda: ({copies})", {"__builtins__": {}})  # generated from numbers only

    def decode(names: Sequence[str]) -> Callable[..., None]:
        lines = [f"d[{name!r}] = {_expr(op)}" for name, op in zip(names, operands, strict=True)]
        return _compile(_function(f"d, {params}" if params else "d", lines))

    return take(*(pad.areas[area] for area in areas)), decode


def loader(pad: Scratchpad, area: str, operands: Sequence[Operand]) -> Callable[[tuple[Any, ...]], None]:
    """A function writing a tuple of levels into their operands of ``area`` (the input terminals), one
    store per register: the operands must not overlap (:func:`overlapping`)."""
    names = [f"v{k}" for k in range(len(operands))]
    lines = [f"{', '.join(names)}, = levels"] if operands else []
    a = f"a{area}"
    bits: dict[int, list[str]] = {}
    for name, op in zip(names, operands, strict=True):
        i = op.index
        if op.width == "bit":
            bits.setdefault(i, []).append(f"({1 << op.bit} if {name} else 0)")
        elif op.width == "byte":
            lines.append(f"{a}[{i}] = int({name}) & 255")
        else:
            lines.append(f"v = int({name})")
            lines += [f"{a}[{i + k}] = v >> {8 * k} & 255" for k in range(SIZE[op.width])]
    for i, terms in bits.items():
        keep = 0xFF & ~sum(1 << op.bit for op in operands if op.width == "bit" and op.index == i)
        lines.append(f"{a}[{i}] = {a}[{i}] & {keep} | {' | '.join(terms)}")
    return partial(_compile(_function(f"levels, {a}", lines)), **{a: pad.areas[area]})


def _expr(op: Operand) -> str:
    a = f"a{op.area}"
    if op.width == "bit":
        return f"{a}[{op.index}] >> {op.bit} & 1 == 1"
    if op.width == "byte":
        return f"{a}[{op.index}]"
    return "(" + " | ".join(f"{a}[{op.index + k}] << {8 * k}" for k in range(SIZE[op.width])) + ")"


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
            size = SIZE[op.width]
            bits = {(op.index + k, b) for k in range(size) for b in range(8)}
        if seen & bits:
            return True
        seen |= bits
    return False
