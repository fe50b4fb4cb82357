"""Straight-line runs of instructions fused into one generated function each (the fast path).

A process runs as ``while pc >= 0: pc = code[pc]()``. Between two places execution can arrive at (a
process start, a label, the instruction after a jump, call, return, end or breakpoint), the instructions
run one after the other, so such a run becomes one function: the common instructions (LD/LDC, WR/WRC,
the logic ones, SET/RES, NEG, comparisons with an operand) as inline code on a local stack variable,
the others (counters, timers, tables in T ...) as calls of their linked closures. The function returns
the index where the run ends, whose own code (a jump's closure, or the next run) goes on. The source is
generated from the decoded operands (numbers only), never from program text, once per download.

Instructions that can fail at run time (a table in R reaching past its end) stay out of the runs, so an
error still names its own line. ``TecomatConfig.fuse = False`` runs every instruction's closure instead
(the tests run the examples both ways).
"""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING

from plcsim.tecomat.memory import Operand

if TYPE_CHECKING:
    from plcsim.tecomat.assembler import Instruction
    from plcsim.tecomat.machine import Machine

Code = Callable[[], int]
ENDS = frozenset({"JMP", "JMD", "JMC", "JMI", "CAL", "CAD", "CAC", "CAI", "RET", "RED", "REC"}) | frozenset(
    {"E", "ED", "EC", "EOC", "BP", "P"}
)
"""The instructions that decide where execution goes on: each ends a run."""
SWITCHES = frozenset({"CHG", "NXT", "PRV"})
_OPS = {"AND": "&", "OR": "|", "XOR": "^"}
_RELATIONS = {"EQ": "==", "LT": "<", "GT": ">"}
_NEGATED = {"ANC": "AND", "ORC": "OR", "XOC": "XOR"}


def fuse(m: Machine, closures: list[Code]) -> list[Code]:
    """``closures`` with each run's first entry replaced by the run's fused function."""
    code = m.asm.code
    alone = [_ends(instr) or not _fusible(instr) for instr in code]
    entries = set(m.asm.processes.values()) | set(m.asm.labels.values())
    entries |= {i + 1 for i, a in enumerate(alone) if a}
    fill = "s[-1]" if m.config.pop_fill_keeps_a7 else "0"
    areas = m.pad.areas
    out = list(closures)
    for start in sorted(e for e in entries if e < len(code) and not alone[e]):
        end = start
        lines: list[str] = []
        while end < len(code) and not alone[end] and (end == start or end not in entries):
            lines += _inline(code[end], end, fill, m.config.ci_in_compare)
            end += 1
        if end - start < 2:
            continue
        source = "def make(m, c, aX, aY, aS, aR, aD, aU):\n    def run():\n        s = m.st\n"
        source += "".join(f"        {line}\n" for line in lines) + f"        return {end}\n    return run\n"
        namespace: dict = {}
        exec(source, {"__builtins__": {}}, namespace)  # generated from decoded operands, not program text
        out[start] = namespace["make"](m, closures, *(areas[a] for a in "XYSRDU"))
    return out


def _ends(instr: Instruction) -> bool:
    return instr.mnemonic in ENDS


def _fusible(instr: Instruction) -> bool:
    """Whether a closure may run inside a run: it never fails (an R table may reach past R's end)."""
    return not (instr.mnemonic in ("LTB", "FTB") and isinstance(instr.arg, Operand))


def _inline(instr: Instruction, index: int, fill: str, ci: bool) -> list[str]:
    m, op = instr.mnemonic, instr.arg
    if m in _RELATIONS and op is not None:
        carry = " + (aS[0] >> 3 & 1)" if ci else ""
        return [
            f"a = s[0]; b = {_value(op, False, mask=False)}{carry}",
            "aS[0] = aS[0] & 248 | (a == b) | (a < b) << 1 | (a <= b) << 2",
            f"s[0] = 65535 if a {_RELATIONS[m]} b else 0",
        ]
    if m == "L":
        return []
    if m == "NEG":
        return ["s[0] ^= 65535"]
    if m in ("LD", "LDC") and isinstance(op, Operand):
        return [f"s.insert(0, {_value(op, m == 'LDC', mask=True)})", "del s[8]"]
    if m in ("WR", "WRC") and not op.is_immediate:
        return _write(op, m == "WRC")
    if m in ("AND", "OR", "XOR", "ANC", "ORC", "XOC"):
        base = _NEGATED.get(m, m)
        sign = _OPS[base]
        if op is None:
            return ["v = s.pop(0)", f"s.append({fill})", f"s[0] {sign}= v"]
        if op.width == "byte" and not op.is_immediate:
            value = _value(op, m != base, mask=False)
            return ["v = s[0]", f"s[0] = v & 65280 | (v & 255 {sign} {value}) & 255"]
        return [f"s[0] {sign}= {_value(op, m != base, mask=True)}"]
    if m in ("SET", "RES"):
        a = f"a{op.area}[{op.index}]"
        if op.width == "bit":
            change = f"{a} |= {1 << op.bit}" if m == "SET" else f"{a} &= {~(1 << op.bit) & 0xFF}"
            return [f"if s[0]: {change}"]
        return [f"{a} |= s[0] & 255"] if m == "SET" else [f"{a} &= ~s[0] & 255"]
    call = [f"c[{index}]()"]
    return call + (["s = m.st"] if m in SWITCHES else [])


def _value(op: Operand, negate: bool, mask: bool) -> str:
    """The operand as the stack sees it: a bit as a 16-bit mask (with ``mask``), a byte, a word, a number."""
    if op.is_immediate:
        return str(~op.value & 0xFFFF if negate else op.value)
    a = f"a{op.area}"
    if op.width == "bit":
        on, off = (0, 65535) if negate else (65535, 0)
        return f"({on} if {a}[{op.index}] >> {op.bit} & 1 else {off})"
    if op.width == "byte":
        return f"({a}[{op.index}] ^ 255)" if negate else f"{a}[{op.index}]"
    word = f"({a}[{op.index}] | {a}[{op.index + 1}] << 8)"
    return f"({word} ^ 65535)" if negate else word


def _write(op: Operand, negate: bool) -> list[str]:
    a = f"a{op.area}[{op.index}]"
    if op.width == "bit":
        on, off = f"{a} |= {1 << op.bit}", f"{a} &= {~(1 << op.bit) & 0xFF}"
        if negate:
            on, off = off, on
        return [f"if s[0]: {on}", f"else: {off}"]
    flip = " ^ 65535" if negate else ""
    if op.width == "byte":
        return [f"{a} = (s[0]{flip}) & 255"]
    return [f"v = s[0]{flip}", f"{a} = v & 255", f"a{op.area}[{op.index + 1}] = v >> 8"]
