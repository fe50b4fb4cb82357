"""Straight-line runs of instructions fused into one generated function each (the fast path).

A process runs as ``while pc >= 0: pc = code[pc]()``. Between two places execution can arrive at (a
process start, a label, the instruction after a jump, call, return, end or breakpoint), the instructions
run one after the other, so such a run becomes one function: the common instructions (LD/LDC, WR/WRC,
the logic ones, SET/RES, NEG, comparisons with an operand) as inline code, the others (counters, timers,
tables in T ...) as calls of their linked closures. The function returns the index where the run ends,
whose own code (a jump's closure, or the next run) goes on. The source is generated from the decoded
operands (numbers only), never from program text, once per download.

Inside a run the stack is simulated while the code is generated: each level is known to hold a value
of the stack as the run found it (``s[k]``), a value computed into a local variable, or the fill a pop
brings in. Loads, logic and comparisons only name locals; the real stack is written once, as a whole,
before a closure that reads it and at the run's end. Pushes past A7 drop it and pops fill A7 exactly as
the machine does, so the stack after a run is the same level for level.

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
    areas = m.pad.areas
    out = list(closures)
    for start in sorted(e for e in entries if e < len(code) and not alone[e]):
        end = start
        run = _Run(m.config.pop_fill_keeps_a7, m.config.ci_in_compare)
        while end < len(code) and not alone[end] and (end == start or end not in entries):
            run.add(code[end], end)
            end += 1
        if end - start < 2:
            continue
        run.sync()
        source = "def make(m, c, aX, aY, aS, aR, aD, aU):\n    def run():\n        s = m.st\n"
        source += "".join(f"        {line}\n" for line in run.lines) + f"        return {end}\n    return run\n"
        namespace: dict = {}
        exec(source, {"__builtins__": {}}, namespace)  # generated from decoded operands, not program text
        out[start] = namespace["make"](m, closures, *(areas[a] for a in "XYSRDU"))
    return out


def _ends(instr: Instruction) -> bool:
    return instr.mnemonic in ENDS


def _fusible(instr: Instruction) -> bool:
    """Whether a closure may run inside a run: it never fails (an R table may reach past R's end)."""
    return not (instr.mnemonic in ("LTB", "FTB") and isinstance(instr.arg, Operand))


IDENTITY = tuple(f"s[{k}]" for k in range(8))


class _Run:
    """The code of one run, and the stack as the generated code will hold it (an expression per level)."""

    def __init__(self, keep_a7: bool, ci: bool):
        self.keep_a7, self.ci = keep_a7, ci
        self.levels: list[str] = list(IDENTITY)
        self.lines: list[str] = []
        self.count = 0

    def local(self, expr: str) -> str:
        """A new local holding ``expr`` now (so later writes to memory do not change it)."""
        name = f"t{self.count}"
        self.count += 1
        self.lines.append(f"{name} = {expr}")
        return name

    def push(self, expr: str) -> None:
        self.levels.insert(0, self.local(expr))
        del self.levels[8]

    def pop(self) -> str:
        top = self.levels.pop(0)
        self.levels.append(self.levels[-1] if self.keep_a7 else "0")
        return top

    def set_top(self, expr: str) -> None:
        self.levels[0] = self.local(expr)

    def sync(self) -> None:
        """Write the simulated stack into the real one (before a closure reads it, at the run's end)."""
        if tuple(self.levels) != IDENTITY:
            self.lines.append(f"s[:] = [{', '.join(self.levels)}]")
            self.levels = list(IDENTITY)

    def add(self, instr: Instruction, index: int) -> None:
        m, op = instr.mnemonic, instr.arg
        top = self.levels[0]
        if m == "L":
            return
        if m == "NEG":
            self.set_top(f"{top} ^ 65535")
        elif m in ("LD", "LDC") and isinstance(op, Operand):
            self.push(_value(op, m == "LDC", mask=True))
        elif m in ("WR", "WRC") and not op.is_immediate:
            self.lines += _write(op, m == "WRC", top)
        elif m in ("AND", "OR", "XOR", "ANC", "ORC", "XOC"):
            base = _NEGATED.get(m, m)
            sign = _OPS[base]
            if op is None:
                a0 = self.pop()
                self.set_top(f"{self.levels[0]} {sign} {a0}")
            elif op.width == "byte" and not op.is_immediate:
                value = _value(op, m != base, mask=False)
                self.set_top(f"{top} & 65280 | ({top} & 255 {sign} {value}) & 255")
            else:
                self.set_top(f"{top} {sign} {_value(op, m != base, mask=True)}")
        elif m in ("SET", "RES"):
            a = f"a{op.area}[{op.index}]"
            if op.width == "bit":
                change = f"{a} |= {1 << op.bit}" if m == "SET" else f"{a} &= {~(1 << op.bit) & 0xFF}"
                self.lines.append(f"if {top}: {change}")
            else:
                self.lines.append(f"{a} |= {top} & 255" if m == "SET" else f"{a} &= ~{top} & 255")
        elif m in _RELATIONS and op is not None:
            a = self.local(top)
            carry = " + (aS[0] >> 3 & 1)" if self.ci else ""
            b = self.local(f"{_value(op, False, mask=False)}{carry}")
            self.lines.append(f"aS[0] = aS[0] & 248 | ({a} == {b}) | ({a} < {b}) << 1 | ({a} <= {b}) << 2")
            self.set_top(f"65535 if {a} {_RELATIONS[m]} {b} else 0")
        else:
            self.sync()
            self.lines.append(f"c[{index}]()")
            if m in SWITCHES:
                self.lines.append("s = m.st")


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


def _write(op: Operand, negate: bool, top: str) -> list[str]:
    a = f"a{op.area}[{op.index}]"
    if op.width == "bit":
        on, off = f"{a} |= {1 << op.bit}", f"{a} &= {~(1 << op.bit) & 0xFF}"
        if negate:
            on, off = off, on
        return [f"if {top}: {on}", f"else: {off}"]
    flip = " ^ 65535" if negate else ""
    if op.width == "byte":
        return [f"{a} = ({top}{flip}) & 255"]
    return [f"v = {top}{flip}", f"{a} = v & 255", f"a{op.area}[{op.index + 1}] = v >> 8"]
