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
>>> lines, names = sampler([parse_address("R2.1"), parse_address("R2.3"), parse_address("R3")], "aR")
>>> function("levels", lines, {**names, "aR": pad.areas["R"]})((True, False, 7)); pad.areas["R"][2:4].hex()
'0207'
>>> lines, names, units = publisher([("B", parse_address("Y1.2")), ("W", parse_address("YW0"))])
>>> class Cpu: outputs = {"B": False, "W": 0}; output_version = 0; _y_keys = [0] * units
>>> cpu = Cpu(); function("c", lines, {**names, "aY": pad.areas["Y"]})(cpu); cpu.outputs, cpu.output_version
({'B': True, 'W': 1024}, 1)
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from functools import partial
from itertools import product
from operator import itemgetter
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
    params = ", ".join(f"a{area}" for area in areas)
    take = eval(f"lambda {params}: lambda: {copies(operands)}", {"__builtins__": {}})  # generated from numbers only

    def decode(names: Sequence[str]) -> Callable[..., None]:
        lines = [f"d[{name!r}] = {_expr(op)}" for name, op in zip(names, operands, strict=True)]
        return _compile(_function(f"d, {params}" if params else "d", lines))

    return take(*(pad.areas[area] for area in areas)), decode


def copies(operands: Sequence[Operand]) -> str:
    """What ``take()`` of :func:`snapshot` returns, as an expression over the areas ``aR``, ``aY`` ... (a
    generated cycle copies them itself)."""
    areas = sorted({op.area for op in operands})
    ends = {a: max(op.index + SIZE[op.width] for op in operands if op.area == a) for a in areas}
    return "(" + "".join(f"a{area}[:{ends[area]}], " for area in areas) + ")"


def sampler(operands: Sequence[Operand], area: str) -> tuple[list[str], dict[str, Any]]:
    """Lines storing ``levels`` (the input levels, one per operand, in order) into the registers of the
    bytearray named ``area`` (the input terminals), one store per register, and the names the lines use. A
    register of bit inputs takes its byte from a table keyed by the tuple of its levels, so the terminals cost
    a lookup each instead of a test per bit. The operands must not overlap (:func:`overlapping`)."""
    lines: list[str] = []
    names: dict[str, Any] = {"int": int}
    bits: dict[int, list[tuple[int, Operand]]] = {}
    for k, op in enumerate(operands):
        if op.width == "bit":
            bits.setdefault(op.index, []).append((k, op))
        else:
            lines.append(f"w = int(levels[{k}])")
            lines += [f"{area}[{op.index + j}] = w{f' >> {8 * j}' if j else ''} & 255" for j in range(SIZE[op.width])]
    for i, group in bits.items():
        positions = [k for k, _ in group]
        if positions == list(range(positions[0], positions[-1] + 1)):
            key = f"levels[{positions[0]}:{positions[-1] + 1}]"
        else:
            names[f"p{i}"] = itemgetter(*positions)  # two or more positions: a tuple
            key = f"p{i}(levels)"
        masks = [1 << op.bit for _, op in group]
        names[f"x{i}"] = _Packed(masks)
        keep = 0xFF & ~sum(masks)
        value = f"x{i}[{key}]"
        lines.append(f"{area}[{i}] = {area}[{i}] & {keep} | {value}" if keep else f"{area}[{i}] = {value}")
    return lines, names


def loader(pad: Scratchpad, area: str, operands: Sequence[Operand]) -> Callable[[tuple[Any, ...]], None]:
    """A function writing a tuple of levels into their operands of ``area`` (the input terminals), by the lines
    of :func:`sampler`: 0.1's name for it, kept for the old import path (:mod:`plcsim.core.moved`)."""
    lines, names = sampler(operands, "terminals")
    return function("levels", lines, {**names, "terminals": pad.areas[area]})


class _Packed(dict):
    """The byte of each tuple of bit levels (every tuple of bools is a key; 0 and 1 find the same entries);
    any other values are packed on the miss, a bit set where its level is true, as the wiring means it."""

    def __init__(self, masks: list[int]):
        super().__init__((levels, self.pack(masks, levels)) for levels in product((False, True), repeat=len(masks)))
        self.masks = masks

    @staticmethod
    def pack(masks: list[int], levels: tuple[Any, ...]) -> int:
        return sum(mask for mask, level in zip(masks, levels, strict=True) if level)

    def __missing__(self, levels: tuple[Any, ...]) -> int:
        return self.pack(self.masks, levels)


def publisher(outputs: Sequence[tuple[str, Operand]]) -> tuple[list[str], dict[str, Any], int]:
    """Lines bringing the outputs' values from Y (``aY``) into ``c.outputs`` after a cycle, the names they use,
    and how many keys they keep in ``c._y_keys``.

    The outputs fall into units, the registers they share (one register of bit outputs, a word ...); a unit's
    key is its registers' bits that outputs occupy, as one number. A unit whose key changed since the cycle
    before updates its outputs from a table of decoded keys, and ``c.output_version`` counts the cycles that
    changed any. A key of 0 is every output of the unit off (what STOP sets)."""
    units: list[list[tuple[str, Operand]]] = []
    ends: list[int] = []
    for name, op in sorted(outputs, key=lambda item: item[1].index):
        if units and op.index < ends[-1]:
            units[-1].append((name, op))
            ends[-1] = max(ends[-1], op.index + SIZE[op.width])
        else:
            units.append([(name, op)])
            ends.append(op.index + SIZE[op.width])
    lines = ["ly = c._y_keys; changed = False"]
    names: dict[str, Any] = {}
    for u, (unit, end) in enumerate(zip(units, ends, strict=True)):
        low = unit[0][1].index
        masks = [0] * (end - low)
        for _, op in unit:
            for j in range(SIZE[op.width]):
                masks[op.index - low + j] |= 1 << op.bit if op.width == "bit" else 0xFF
        terms = [f"aY[{low + j}]" + (f" & {mask}" if mask != 0xFF else "") for j, mask in enumerate(masks)]
        terms = [f"({term}) << {8 * j}" if j else term for j, term in enumerate(terms)]
        decoded = ", ".join(f"{name!r}: {_decoded(op, low)}" for name, op in unit)
        names[f"u{u}"] = _Decoded(_compile(f"def f(key):\n    return {{{decoded}}}\n"))
        lines += [
            f"y{u} = {' | '.join(terms)}",
            f"if y{u} != ly[{u}]: ly[{u}] = y{u}; c.outputs.update(u{u}[y{u}]); changed = True",
        ]
    lines.append("if changed: c.output_version += 1")
    return lines, names, len(units)


def _decoded(op: Operand, low: int) -> str:
    """The operand's value (a bit as a bool) in the key of the unit starting at register ``low``."""
    shift = 8 * (op.index - low)
    if op.width == "bit":
        return f"key >> {shift + op.bit} & 1 == 1"
    return f"key >> {shift} & {(1 << 8 * SIZE[op.width]) - 1}"


class _Decoded(dict):
    """The outputs of a unit by name for each key seen (filled when first needed, 4096 kept)."""

    def __init__(self, decode: Callable[[int], dict[str, Any]]):
        super().__init__()
        self.decode = decode

    def __missing__(self, key: int) -> dict[str, Any]:
        value = self.decode(key)
        if len(self) < 4096:
            self[key] = value
        return value


def function(params: str, lines: list[str], names: dict[str, Any]) -> Callable[..., Any]:
    """``def f(params)`` running ``lines``, with ``names`` bound (generated from numbers and quoted names)."""
    source = f"def make({', '.join(names)}):\n    def f({params}):\n"
    source += "".join(f"        {line}\n" for line in lines or ["pass"]) + "    return f\n"
    namespace: dict[str, Any] = {}
    exec(source, {"__builtins__": {}}, namespace)
    return namespace["make"](*names.values())


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
