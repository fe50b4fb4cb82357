"""Python source for a ``.mech`` program's decoded instructions: one function per network and one for the
whole scan, planned once per download (as the Python front end merges OB1 and the Tecomat fuses runs).

A segment is cut into blocks where control can enter it: its start, a label a jump names, the instruction
after each state (where a mechanism resumes). A segment without jumps or states is straight code; any
other is a loop over its blocks (``pc``), a mechanism's entered at its continuation (``m.cont``). RLO and
DR are locals, handed from network to network through ``regs``.

>>> ops = [(0, 0, "A", False), (3, 0, "Y", False)]  # LDR A / WR Y, as decoded
>>> print("\\n".join(segment_lines(ops, None, frozenset({"Y"}), {})))
rlo = d['A']
d['Y'] = rlo
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from typing import Any

from plcsim.controllers.plc836.grammar import TIME_UNIT_MS
from plcsim.controllers.s7.instructions.mechanisms import HOLD, PASS

LDR, LO, LA, WR, FL, LOD, STO, JUM, INIT, STATE, END = range(11)
TAG, BIT, CONST, CELL, LINE = range(5)
_STEP = "    "


def _read_bit(kind: int, name: str, negate: bool) -> str:
    text = f"d[{name!r}]" if kind == TAG else f"d[{name!r}].ACTIVE"
    return f"(not {text})" if negate else text


def _value(kind: int, key: Any, extra: Any, cells: Mapping[int, str]) -> str:
    if kind == CONST:
        return repr(key)
    if kind == TAG:
        return f"d[{key!r}]"
    if kind == LINE:
        return f"d[{key!r}].LINE"
    data, offset = key
    name = cells[id(data)]
    return f"{name}[{offset}]" if extra == 1 else f"({name}[{offset}] | {name}[{offset + 1}] << 8)"


def _write_bit(kind: int, name: str, value: str, direct: frozenset[str]) -> str:
    if kind == BIT:
        return f"d[{name!r}].ACTIVE = {value}"
    if name in direct:
        return f"d[{name!r}] = {value}"
    return f"store(t, {name!r}, {value})"


def _blocks(ops: list[tuple[Any, ...]], mech: str | None) -> list[int]:
    starts = {1 if mech else 0}
    for pc, o in enumerate(ops):
        if o[0] == JUM:
            starts.add(o[1])
        elif o[0] == STATE:
            starts.add(pc + 1)
            if o[7] >= 0:
                starts.add(o[7])
    return sorted(s for s in starts if s < len(ops))


def segment_lines(
    ops: list[tuple[Any, ...]], mech: str | None, direct: frozenset[str], cells: Mapping[int, str]
) -> list[str]:
    """The body of one segment (indented from 0), using ``t``, ``d`` (the tags' dict), ``rlo``, ``dr``."""
    looped = mech is not None or any(o[0] == JUM for o in ops)
    starts = _blocks(ops, mech)
    out: list[str] = []
    body: list[str] = []
    for k, start in enumerate(starts):
        end = starts[k + 1] if k + 1 < len(starts) else len(ops)
        lines = _block(ops, start, end, direct, cells, looped)
        if looped:
            body.append(f"{'if' if k == 0 else 'elif'} pc == {start}:")
            body += [_STEP + line for line in lines]
        else:
            body += lines
    if not looped:
        return body
    if mech is None:
        out.append("pc = 0")
    else:
        out += [f"m = d[{mech!r}]", "if m.begin():", _STEP + "iec = m.iec", _STEP + "pc = m.cont or 1"]
    indent = _STEP if mech is not None else ""
    out.append(indent + "while True:")
    out += [indent + _STEP + line for line in body]
    out += [indent + _STEP + "else:", indent + _STEP * 2 + "break"]
    if mech is not None:
        out.append(_STEP + "m.end()")
    return out


def _block(
    ops: list[tuple[Any, ...]], start: int, end: int, direct: frozenset[str], cells: Mapping[int, str], looped: bool
) -> list[str]:
    out: list[str] = []
    for pc in range(start, end):
        o = ops[pc]
        code = o[0]
        if code == LDR:
            out.append(f"rlo = {_read_bit(o[1], o[2], o[3])}")
        elif code == LO:
            out.append(f"rlo = rlo or {_read_bit(o[1], o[2], o[3])}")
        elif code == LA:
            out.append(f"rlo = rlo and {_read_bit(o[1], o[2], o[3])}")
        elif code == WR:
            out.append(_write_bit(o[1], o[2], "rlo", direct))
        elif code == FL:
            out.append(_write_bit(o[1], o[2], repr(o[4]), direct))
        elif code == LOD:
            out.append(f"dr = {_value(o[1], o[2], o[3], cells)}")
        elif code == STO:
            if o[1] == TAG:
                out.append(f"store(t, {o[2]!r}, dr)")
            else:
                data, offset = o[2]
                name = cells[id(data)]
                out.append(f"{name}[{offset}] = dr & 0xFF")
                if o[3] == 2:
                    out.append(f"{name}[{offset + 1}] = (dr >> 8) & 0xFF")
        elif code == INIT:
            out.append(f"d[{o[1]!r}].init()")
        elif code == JUM:
            if o[1] <= pc:
                out.append("tick()")
            out += [f"pc = {o[1]}", "continue"]
            return out
        elif code == STATE:
            out += _state(o, pc, cells)
            return out
        elif code == END:
            out.append("break")
            return out
    if looped:
        out += [f"pc = {end}", "continue"] if end < len(ops) else ["break"]
    return out or ["pass"]


def _state(o: tuple[Any, ...], pc: int, cells: Mapping[int, str]) -> list[str]:
    _, kind, n, line, lkind, lkey, lextra, label_pc, label, code, counter = o
    if lkind is None:
        limit = "None"
    elif lkind == CONST:
        limit = repr(lkey * TIME_UNIT_MS)
    else:
        limit = f"{_value(lkind, lkey, lextra, cells)} * {TIME_UNIT_MS}"
    out = [
        f"r = m.state({kind!r}, {n}, {line}, bool(rlo), {limit}, {label!r}, {code or 0}"
        + (f", counters[{counter!r}])" if counter is not None else ")"),
        f"if r == {PASS}:",
        f"{_STEP}m.cont = pc = {pc + 1}",
        f"{_STEP}if iec:",
        f"{_STEP * 2}break",
        f"{_STEP}continue",
        f"if r == {HOLD}:",
        f"{_STEP}break",
    ]
    if code is not None:
        out.append(f"dr = {code}")
    out += [f"m.cont = pc = {label_pc}", "if iec:", f"{_STEP}break", "continue"]
    return out


def compile_functions(
    segments: list[list[str]],
    namespace: dict[str, Any],
    filename: str,
) -> tuple[list[Callable[[Any], None]], Callable[[Any], None]]:
    """One function per segment and one running them all in order (the whole scan)."""
    header = ["    d = t.__dict__", "    rlo, dr = regs"]
    footer = ["    regs[0] = rlo", "    regs[1] = dr"]
    source: list[str] = []
    for k, lines in enumerate(segments):
        source += [f"def network_{k}(t):", *header, *(_STEP + line for line in lines), *footer, ""]
    source += ["def whole(t):", *header]
    for lines in segments:
        source += [_STEP + line for line in lines]
    source += [*footer, ""]
    exec(compile("\n".join(source), f"<{filename}>", "exec"), namespace)
    return [namespace[f"network_{k}"] for k in range(len(segments))], namespace["whole"]
