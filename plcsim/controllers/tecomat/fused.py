"""Straight-line runs of instructions compiled into one generated function each (the fast path).

A process runs as ``while pc >= 0: pc = code[pc]()``. Between two places execution can arrive at (a
process start, a label, the instruction after a jump, call, return, end or breakpoint), the instructions
run one after the other, so such a run becomes one function, generated once per download from the
decoded operands (numbers only, never program text). A process without jumps is one run, so one call.
The function returns the index where the run ends, whose own code (a jump's closure, the next run) goes on.

Inside a run the stack lives in locals: while the code is generated, each level is known to hold a value
of the stack as the run found it (``s[k]``), a local computed by an earlier instruction, or the fill a
pop brings in; the real stack is written once, as a whole, before a closure that reads it and at the
run's end. A level that holds a boolean (a bit LD, a comparison, LET, logic between booleans) is kept as
a Python truth value and turned into the machine's mask 0000H/FFFFH only where a number is needed. The
registers of X, Y, R, D and U the run touches are read into locals once and written back once (three or
more neighbours as one slice), a word read as a number once while its registers keep, and bits are tested,
set and cleared by tables of the 256 byte values. A local that only the next line uses is written into it.
Function blocks are written out in place, statement for statement as their cores in
:mod:`plcsim.controllers.tecomat.blocks` (the levels as inputs, the word in the held registers, the hidden
state an object the code is given); the rest (tables, CHG ...) call their closures. The S0 flags a
comparison sets are written only if something can read them before the next instruction that sets all
three again, and a block's S0 write only if something can read it before the next counter or timer.
Pushes past A7 drop it and pops fill A7 exactly as the machine does, so the stack after a run is the same
level for level.

Instructions that can fail at run time (a table in R reaching past its end) stay out of the runs, so an
error still names its own line. A program whose only process is P0 and whose P0 is one run may have its
whole cycle generated around that run (``cycle`` of :func:`fuse`): then a cycle is one call.
``TecomatConfig.fuse = False`` runs every instruction's closure instead (the tests run the examples both
ways, and compare the two on random programs).
"""

from __future__ import annotations

import re
from collections import Counter
from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING, NamedTuple

from plcsim.controllers.tecomat.blocks import BLOCKS, state_of
from plcsim.controllers.tecomat.machine import END
from plcsim.controllers.tecomat.memory import Operand
from plcsim.controllers.tecomat.settings import TIME_BASES_NS

if TYPE_CHECKING:
    from plcsim.controllers.tecomat.assembly import Instruction
    from plcsim.controllers.tecomat.machine import Machine

Code = Callable[[], int]
ENDS = frozenset({"JMP", "JMD", "JMC", "JMI", "CAL", "CAD", "CAC", "CAI", "RET", "RED", "REC"}) | frozenset(
    {"E", "ED", "EC", "EOC", "BP", "P"}
)
"""The instructions that decide where execution goes on: each ends a run."""
SWITCHES = frozenset({"CHG", "NXT", "PRV"})
SETS_S0 = frozenset({"CTU", "CTD", "CNT", "TON", "RTO"})
"""Blocks that always write all of S0 and never read it (so flags pending before them are dead)."""
AREAS = "XYSRDU"
_OPS = {"AND": "&", "OR": "|", "XOR": "^"}
_RELATIONS = {"EQ": "==", "LT": "<", "GT": ">"}
_NEGATED = {"ANC": "AND", "ORC": "OR", "XOC": "XOR"}
BIT_OF = tuple(tuple(value >> bit & 1 == 1 for value in range(256)) for bit in range(8))
"""``BIT_OF[k][v]``: bit k of the byte v, as a bool."""
SET_OF = tuple(tuple(value | 1 << bit for value in range(256)) for bit in range(8))
CLEAR_OF = tuple(tuple(value & ~(1 << bit) for value in range(256)) for bit in range(8))
"""``SET_OF[k][v]``, ``CLEAR_OF[k][v]``: the byte v with bit k set, cleared."""
_REGISTER = re.compile(r"\ba([XYRDU])\[(\d+)\]")
_LOCAL = re.compile(r"(?<![.\w])t\d+\b")
"""A local of the run (not ``m.t0``)."""
_DEFINITION = re.compile(r"(t\d+) = (.*)")
_READ = re.compile(r"m[XYRDU]\d+ = a[XYRDU]\[\d+\]")


class Level(NamedTuple):
    """One stack level as the generated code holds it: an expression, and whether it is a boolean
    (a truth value standing for the mask FFFFH or 0000H) rather than the 16-bit number itself."""

    expr: str
    boolean: bool = False


IDENTITY = tuple(Level(f"s[{k}]") for k in range(8))


@dataclass
class Cycle:
    """What a caller adds around the run of a program's only process to make it a whole cycle: the lines
    before the run (the turnaround at ``t0``) and after it (the cycle's end), and the names they use;
    :func:`fuse` sets ``head`` to the generated function if the program is of that kind."""

    before: list[str]
    after: list[str]
    """(A register read ``aY[3]`` in these lines becomes the run's local ``mY3`` where the run holds it: at the
    run's end the locals it holds are what memory holds.)"""
    names: dict[str, object]
    head: Callable[..., int] | None = None


def fuse(m: Machine, closures: list[Code], cycle: Cycle | None = None) -> list[Code]:
    """``closures`` with each run's first entry replaced by the run's generated function.

    With ``cycle``, a program whose only process is P0 (P60 aside) and whose P0 is one run gets that run
    as ``run(start=None)``: called without ``start`` it is P0's run as any other; ``run(start)`` is the whole
    cycle starting at ``start`` (``cycle.before``, P0, ``cycle.after``) in one call. Generated once, it serves both."""
    code = m.asm.code
    alone = [_ends(instr) or not _fusible(instr) for instr in code]
    entries = set(m.asm.processes.values()) | set(m.asm.labels.values())
    entries |= {i + 1 for i, a in enumerate(alone) if a}
    head = m.asm.processes[0] if cycle is not None and set(m.asm.processes) <= {0, 60} else None
    out = list(closures)
    for start in sorted(e for e in entries if e < len(code) and not alone[e]):
        end = start
        run = _Run(m, m.config.pop_fill_keeps_a7, m.config.ci_in_compare)
        while end < len(code) and not alone[end] and (end == start or end not in entries):
            run.add(code[end], end, closures[end])
            end += 1
        length = end - start
        if end < len(code) and code[end].mnemonic == "E" and code[end].process != 60:
            whole, end = start == head, END  # outside P60 nothing is called when a process ends (E checks that)
        else:
            whole = False
        if length < 2 and not whole:
            continue
        run.finish()
        names = {"m": m, **{f"a{area}": m.pad.areas[area] for area in AREAS}, **run.bound}
        if whole:
            assert cycle is not None
            lines = ["if start is not None:", *(f"    {line}" for line in cycle.before), "s = m.st", *run.lines]
            lines += [f"if start is None: return {end}", *(run.as_held(line) for line in cycle.after)]
            names |= cycle.names
            signature = "run(start=None)"
        else:
            lines, signature = ["s = m.st", *run.lines], "run()"
        source = f"def make({', '.join(names)}):\n    def {signature}:\n"
        source += "".join(f"        {line}\n" for line in lines) + f"        return {end}\n    return run\n"
        namespace: dict = {}
        exec(source, {"__builtins__": {}}, namespace)  # generated from decoded operands, not program text
        out[start] = namespace["make"](*names.values())
        if whole:
            cycle.head = out[start]  # type: ignore[union-attr]
    return out


def _ends(instr: Instruction) -> bool:
    return instr.mnemonic in ENDS


def _fusible(instr: Instruction) -> bool:
    """Whether a closure may run inside a run: it never fails (an R table may reach past R's end)."""
    return not (instr.mnemonic in ("LTB", "FTB") and isinstance(instr.arg, Operand))


def _reads_s(op: object) -> bool:
    return isinstance(op, Operand) and op.area == "S"


class _Run:
    """The code of one run, the stack as the generated code will hold it, and the registers it holds.

    Every register of X, Y, R, D, U the run touches is read into a local once (``mY0``) and written back
    once at the run's end (or before a closure that may read it, or a block core that works on it). S
    stays in memory: the system flags are read and written by the cores, the closures and the pending
    S0 write."""

    def __init__(self, m: Machine, keep_a7: bool, ci: bool):
        self.m, self.keep_a7, self.ci = m, keep_a7, ci
        self.levels: list[Level] = list(IDENTITY)
        self.lines: list[str] = []
        self.bound: dict[str, Callable] = {}
        """Names the generated code calls (closures ``c<i>``, block cores ``k<i>``) and what they are."""
        self.count = 0
        self.pending_flags: str | None = None
        """The S0 write of the last comparison, not emitted yet (a later one may make it dead)."""
        self.ci_zero = False
        """S0.3 (the carry-in) is known to be 0: a counter or timer cleared it, and nothing set it since."""
        self.high_zero = False
        """S0.3..S0.7 are known to be 0: a counter wrote S0, and nothing but comparisons and ADD (which keep
        them) wrote it since; a comparison's flags then need not read S0."""
        self.flag_writes: list[int] = []
        """The lines where blocks write S0 that nothing may have read yet: a counter or timer that writes all
        of S0 makes them dead, and they are dropped (read S0 first: :meth:`flags_read`)."""
        self.held_registers: dict[tuple[str, int], str] = {}
        self.changed: dict[tuple[str, int], str] = {}
        """The held registers written since they were read (to write back), in the order first written."""
        self.words: dict[tuple[str, int], str] = {}
        """The local holding each word read as a number since neither of its registers changed (read once)."""

    # -- registers ------------------------------------------------------------------------------------

    def reg(self, area: str, index: int) -> str:
        """The register as the code names it: a local holding it (read now if not held yet), ``aS[i]`` for S."""
        if area == "S":
            return f"aS[{index}]"
        key = (area, index)
        name = self.held_registers.get(key)
        if name is None:
            name = self.held_registers[key] = f"m{area}{index}"
            self.lines.append(f"{name} = a{area}[{index}]")
        return name

    def as_held(self, line: str) -> str:
        """``line`` with each register ``aR[5]`` it reads the run holds as that local (at the run's end, after
        :meth:`finish`, the locals are what memory holds: this saves a line after the run reading them again)."""
        return _REGISTER.sub(lambda m: self.held_registers.get((m[1], int(m[2])), m[0]), line)

    def wrote(self, area: str, index: int) -> None:
        self.words.pop((area, index), None)
        self.words.pop((area, index - 1), None)
        if area != "S":
            self.changed[(area, index)] = self.held_registers[(area, index)]

    def write_back(self, keys: list[tuple[str, int]] | None = None, forget: bool = False) -> None:
        """Store the changed held registers (only ``keys`` if given) into memory; ``forget``: stop holding them.

        Three or more neighbours the run holds are stored as one slice (one held but unchanged among them
        stores what memory already has)."""
        stored = list(self.changed) if keys is None else [k for k in keys if k in self.changed]
        for area in sorted({key[0] for key in stored}):
            groups: list[list[int]] = []
            for index in sorted(key[1] for key in stored if key[0] == area):
                last = groups[-1][-1] if groups else None
                if last is not None and all((area, i) in self.held_registers for i in range(last + 1, index)):
                    groups[-1] += range(last + 1, index + 1)
                else:
                    groups.append([index])
            for group in groups:
                if len(group) >= 3:
                    held = ", ".join(self.held_registers[(area, i)] for i in group)
                    self.lines.append(f"a{area}[{group[0]}:{group[-1] + 1}] = ({held})")
                else:
                    self.lines += [f"a{area}[{i}] = {self.held_registers[(area, i)]}" for i in group]
                for i in group:
                    self.changed.pop((area, i), None)
        if forget:
            self.words.clear()
            for key in list(self.held_registers) if keys is None else keys:
                self.held_registers.pop(key, None)

    def bit(self, op: Operand) -> str:
        """An expression true iff the bit operand is 1: a table of the bit in every byte value, a subscript
        Python runs faster than ``&`` (which it does not specialise) and a bool ``if`` tests at once."""
        return self.test(self.reg(op.area, op.index), op.bit)

    def test(self, register: str, bit: int) -> str:
        """Bit ``bit`` of the register as a bool (see :meth:`bit`)."""
        self.bound[f"bit{bit}"] = BIT_OF[bit]
        return f"bit{bit}[{register}]"

    def setting(self, register: str, bit: int, on: bool) -> str:
        """The statement setting (``on``) or clearing bit ``bit`` of the register, by a table as :meth:`bit`."""
        name = f"{'set' if on else 'clear'}{bit}"
        self.bound[name] = (SET_OF if on else CLEAR_OF)[bit]
        return f"{register} = {name}[{register}]"

    def number(self, op: Operand, negate: bool) -> str:
        """A byte, word or immediate operand as a number (a byte negated in 8 bits, the rest in 16)."""
        if op.is_immediate:
            return str(~op.value & 0xFFFF if negate else op.value)
        low = self.reg(op.area, op.index)
        if op.width == "byte":
            return f"({low} ^ 255)" if negate else low
        key = (op.area, op.index)
        word = self.words.get(key)
        if op.area == "S":  # (S changes behind the run's back: flags, closures)
            word = f"({low} | {self.reg(op.area, op.index + 1)} << 8)"
        elif word is None:
            word = self.words[key] = self.local(f"{low} | {self.reg(op.area, op.index + 1)} << 8").expr
        return f"({word} ^ 65535)" if negate else word

    # -- levels ---------------------------------------------------------------------------------------

    def local(self, expr: str, boolean: bool = False) -> Level:
        """A new local holding ``expr`` now (so later writes to registers do not change it)."""
        name = f"t{self.count}"
        self.count += 1
        self.lines.append(f"{name} = {expr}")
        return Level(name, boolean)

    def held(self, expr: str) -> str:
        """``expr`` if it is a level's local or a number (nothing can change it), else a new local holding it."""
        return expr if expr.isdigit() or (expr[0] == "t" and expr[1:].isdigit()) else self.local(expr).expr

    @staticmethod
    def num(level: Level) -> str:
        """The level as the machine's 16-bit number."""
        return f"(65535 if {level.expr} else 0)" if level.boolean else level.expr

    def push(self, level: Level) -> None:
        self.levels.insert(0, level)
        del self.levels[8]

    def pop(self) -> Level:
        top = self.levels.pop(0)
        self.levels.append(self.levels[-1] if self.keep_a7 else Level("0"))
        return top

    def sync(self) -> None:
        """Write the held stack into the real one (before a closure reads it, at the run's end)."""
        if tuple(self.levels) != IDENTITY:
            self.lines.append(f"s[:] = [{', '.join(self.num(level) for level in self.levels)}]")
            self.levels = list(IDENTITY)

    def flush(self) -> None:
        """Emit the pending S0 write (something may read S0 next)."""
        if self.pending_flags is not None:
            self.flags_read()  # (it keeps S0.3..S0.7 as the blocks wrote them)
            self.lines.append(self.pending_flags)
            self.pending_flags = None

    def finish(self) -> None:
        self.flush()
        self.sync()
        self.write_back()
        self.lines = _inlined(_without_dead(self.lines))

    def flags_read(self) -> None:
        """Something may read S0 here: the blocks' writes so far are live."""
        self.flag_writes.clear()

    def flag_write(self, line: str) -> None:
        """A block's line writing S0 (and nothing else)."""
        self.flag_writes.append(len(self.lines))
        self.lines.append(line)

    def overwrite_flags(self) -> None:
        """A block writes all of S0 next, reading none of it: the blocks' writes nothing read are dead."""
        for k in self.flag_writes:
            line = self.lines[k]
            self.lines[k] = line[: len(line) - len(line.lstrip())] + "pass"  # dropped by finish()
        self.flag_writes.clear()

    # -- instructions ---------------------------------------------------------------------------------

    def add(self, instr: Instruction, index: int, closure: Code) -> None:
        m, op = instr.mnemonic, instr.arg
        if m == "L":
            return
        if _reads_s(op):
            self.flush()
            self.flags_read()
            self.ci_zero = self.high_zero = False
        top = self.levels[0]
        if m == "NEG":
            self.levels[0] = self.local(f"not {top.expr}", True) if top.boolean else self.local(f"{top.expr} ^ 65535")
        elif m in ("LD", "LDC") and _plain(op):
            negate = m == "LDC"
            if op.width == "bit":
                self.push(self.local(f"{'not ' if negate else ''}{self.bit(op)}", True))
            else:  # (a number, a local holding the word, or an expression to hold)
                self.push(Level(self.held(self.number(op, negate))))
        elif m in ("WR", "WRC", "PUT") and _plain(op) and not op.is_immediate:
            self._write(op, m == "WRC", m == "PUT", top)
        elif m in ("AND", "OR", "XOR", "ANC", "ORC", "XOC"):
            self._logic(_NEGATED.get(m, m), m in _NEGATED, op, top)
        elif m in ("SET", "RES"):
            self._set_res(op, m == "SET", top)
        elif m == "LET" and op.width == "bit":
            a = self.reg(op.area, op.index)
            edge = f"t{self.count}"
            self.count += 1
            self.lines += [
                f"if {top.expr}: {edge} = not {self.test(a, op.bit)}; {self.setting(a, op.bit, True)}",
                f"else: {edge} = False; {self.setting(a, op.bit, False)}",
            ]
            self.wrote(op.area, op.index)
            self.levels[0] = Level(edge, True)
        elif m in _RELATIONS:
            self._compare(_RELATIONS[m], op)
        elif m in BLOCKS:
            self._block(m, index, instr)
        else:
            self._closure(m, index, closure)

    def _write(self, op: Operand, negate: bool, conditional: bool, top: Level) -> None:
        a = self.reg(op.area, op.index)
        if op.width == "bit":
            on, off = self.setting(a, op.bit, True), self.setting(a, op.bit, False)
            if negate:
                on, off = off, on
            lines = [f"if {top.expr}: {on}", f"else: {off}"]
        else:
            flip = " ^ 65535" if negate else ""
            lines = [f"v = {self.num(top)}{flip}", f"{a} = v & 255"]
            if op.width == "word":
                lines.append(f"{self.reg(op.area, op.index + 1)} = v >> 8")
                self.wrote(op.area, op.index + 1)
        self.wrote(op.area, op.index)
        if conditional:  # PUT: only if S1.0
            lines = ["if aS[1] & 1:", *(f"    {line}" for line in lines)]
        self.lines += lines

    def _logic(self, base: str, negate: bool, op: Operand | None, top: Level) -> None:
        sign = _OPS[base]
        if op is None:  # A1 op A0, the stack drops
            a0 = self.pop()
            a1 = self.levels[0]
            if a0.boolean and a1.boolean:
                self.levels[0] = self._boolean(base, a1.expr, a0.expr)
            else:
                self.levels[0] = self.local(f"{self.num(a1)} {sign} {self.num(a0)}")
        elif op.width == "bit" and not op.is_immediate:
            bit = f"{'not ' if negate else ''}{self.bit(op)}"
            if top.boolean:
                self.levels[0] = self._boolean(base, top.expr, bit)
            elif base == "AND":
                self.levels[0] = self.local(f"{top.expr} if {bit} else 0")
            elif base == "OR":
                self.levels[0] = self.local(f"65535 if {bit} else {top.expr}")
            else:
                self.levels[0] = self.local(f"{top.expr} ^ 65535 if {bit} else {top.expr}")
        elif op.width == "byte" and not op.is_immediate:
            a0 = self.local(self.num(top))
            value = self.number(op, negate)
            self.levels[0] = self.local(f"{a0.expr} & 65280 | ({a0.expr} & 255 {sign} {value}) & 255")
        else:
            self.levels[0] = self.local(f"{self.num(top)} {sign} {self.number(op, negate)}")

    def _boolean(self, base: str, left: str, right: str) -> Level:
        if base == "XOR":
            return self.local(f"(not {left}) != (not ({right}))", True)
        return self.local(f"{left} {base.lower()} ({right})", True)

    def _set_res(self, op: Operand, setting: bool, top: Level) -> None:
        a = self.reg(op.area, op.index)
        if op.width == "bit":
            change = self.setting(a, op.bit, setting)
            self.lines.append(f"if {top.expr}: {change}")
        else:
            value = self.num(top)
            self.lines.append(f"{a} |= {value} & 255" if setting else f"{a} &= ~{value} & 255")
        self.wrote(op.area, op.index)

    def _compare(self, relation: str, op: Operand | None) -> None:
        if op is None:  # A1 is the left side; A0 is replaced
            a, b = self.held(self.num(self.levels[1])), self.held(self.num(self.levels[0]))
        else:
            a, b = self.held(self.num(self.levels[0])), self.held(self.number(op, False))
        if self.ci and not self.ci_zero:
            self.flags_read()
            b = self.local(f"{b} + (aS[0] >> 3 & 1)").expr
        kept = "" if self.high_zero else "aS[0] & 248 | "
        self.pending_flags = f"aS[0] = {kept}{_relation_flags(a, b)}"
        self.levels[0] = self.local(f"{a} {relation} {b}", True)

    def _block(self, mnemonic: str, index: int, instr: Instruction) -> None:
        """The block written out in place, step for step as its core in :mod:`.blocks` (the word held in locals)."""
        shape = BLOCKS[mnemonic][1]
        if mnemonic in SETS_S0:
            self.pending_flags = None
            self.overwrite_flags()
            self.ci_zero = True
        else:  # TOF, IMP write S0.3 = 0 or leave S0 alone, the shift registers leave it
            self.flush()
        word = getattr(instr.arg, "word", instr.arg).index
        state = f"b{index}"
        self.bound[state] = state_of(self.m, instr)
        lo, hi = self.reg("R", word), self.reg("R", word + 1)
        self.wrote("R", word)
        self.wrote("R", word + 1)
        inputs = [level.expr for level in self.levels[shape.inputs - 1 :: -1]]
        if shape.preset:
            inputs[-1] = self.held(self.num(self.levels[0]))
        write = _Block(self, state, lo, hi, instr)
        outputs = getattr(write, _WRITERS[mnemonic])(*inputs)
        if mnemonic not in _TIMERS:  # a counter's or shift register's first output is its word's new value
            self.words[("R", word)] = outputs[0].expr
        if mnemonic in SETS_S0 or mnemonic in _TIMERS:  # a counter leaves S0.3..S0.7 at 0, a timer may not
            self.high_zero = mnemonic not in _TIMERS
        if shape.push:
            self.push(outputs[0])
        else:
            self.levels[0] = outputs[0]
        for level, out in zip(shape.places[1:], outputs[1:], strict=True):
            self.levels[level] = out

    def _closure(self, mnemonic: str, index: int, closure: Code) -> None:
        if mnemonic == "ADD":
            self.pending_flags = None  # ADD writes S0.0..S0.2 and reads only S0.3, which a comparison keeps
        else:
            self.flush()
            self.ci_zero = self.high_zero = False
        self.flags_read()  # (ADD reads S0.3)
        self.sync()
        self.write_back(forget=True)  # the closure may read or write any register
        name = f"c{index}"
        self.bound[name] = closure
        self.lines.append(f"{name}()")
        if mnemonic in SWITCHES:
            self.lines.append("s = m.st")


def _relation_flags(a: str, b: str) -> str:
    """S0.0 (a = b), S0.1 (a < b), S0.2 (a <= b) as one number: 5, 6 or 0."""
    return f"(5 if {a} == {b} else 6 if {a} < {b} else 0)"


def _without_dead(lines: list[str]) -> list[str]:
    """``lines`` without the ``pass`` lines dead S0 writes left, but where a block would be empty without one."""
    out: list[str] = []
    for k, line in enumerate(lines):
        if line.strip() == "pass":
            indent = len(line) - len(line.lstrip())
            following = lines[k + 1] if k + 1 < len(lines) else ""
            alone = bool(out) and out[-1].endswith(":") and len(following) - len(following.lstrip()) < indent
            if not alone:
                continue
        out.append(line)
    return out


def _inlined(lines: list[str]) -> list[str]:
    """``lines`` with each local ``tN = expr`` that one line uses, the line right after it (register reads
    aside), written into that use as ``(expr)``: where the use is what the line evaluates first (an ``if``'s
    condition, an assignment's value). The expressions are pure and nothing runs between the two places, so the
    value is the same; a local stored and loaded again costs two operations of every cycle."""
    uses = Counter(_LOCAL.findall("\n".join(lines)))
    out: list[str] = []
    for line in lines:
        spot = _first_evaluated(line)
        if spot is not None:
            names = {n for n in _LOCAL.findall(line[spot[0] : spot[1]]) if uses[n] == 2}
            k = len(out) - 1
            while k >= 0 and _READ.fullmatch(out[k]):
                k -= 1
            found = _DEFINITION.fullmatch(out[k]) if k >= 0 and ";" not in out[k] else None
            if found and found[1] in names and not any(read.split(" ")[0] in found[2] for read in out[k + 1 :]):
                hit = re.compile(rf"(?<![.\w]){found[1]}\b").search(line, *spot)
                assert hit is not None
                line = f"{line[: hit.start()]}({found[2]}){line[hit.end() :]}"
                del out[k]
        out.append(line)
    return out


def _first_evaluated(line: str) -> tuple[int, int] | None:
    """Where in a line of the run's top level is what it evaluates before it changes anything: an ``if``'s
    condition or the value of a plain assignment (None for other lines)."""
    if line[:1] == " " or ";" in line.split(":")[0]:
        return None
    if line.startswith("if "):
        return 3, line.index(":")
    if line.startswith(("else", "elif")) or ";" in line or " = " not in line:
        return None
    return line.rindex(" = ") + 3, len(line)


def _plain(op: object) -> bool:
    """An operand the generated code reads and writes itself (not a long one: those run as closures)."""
    return isinstance(op, Operand) and op.width != "long"


_WRITERS = {"CTU": "counter", "CTD": "counter", "CNT": "cnt", "SFL": "shift", "SFR": "shift"} | {
    m: m.lower() for m in ("TON", "TOF", "IMP", "RTO")
}
"""Which method of :class:`_Block` writes each block out."""
_TIMERS = frozenset({"TON", "TOF", "IMP", "RTO"})


class _Block:
    """One function block's code, written into its run: each method takes the input levels' expressions
    (A(n-1) first, a preset as its number) and returns the output levels, as the core returns its outputs.
    The lines mirror the cores of :mod:`.blocks` statement by statement; ``lo``, ``hi`` hold the word."""

    def __init__(self, run: _Run, state: str, lo: str, hi: str, instr: Instruction):
        self.run, self.b, self.lo, self.hi, self.instr = run, state, lo, hi, instr
        config = run.m.config
        self.preset, self.top = config.ctd_set_value, config.timer_max
        self.per_timer = config.timer_ticks == "per_timer"

    def name(self) -> str:
        name = f"t{self.run.count}"
        self.run.count += 1
        return name

    def emit(self, *lines: str) -> None:
        self.run.lines.extend(lines)

    # -- counters and shift registers --------------------------------------------------------------

    def counter(self, count: str, clear: str) -> list[Level]:
        up = self.instr.mnemonic == "CTU"
        b, lo, hi = self.b, self.lo, self.hi
        c, edge, v, carry = self.name(), self.name(), self.name(), self.name()
        self.emit(
            f"{c} = {count} != 0",
            f"{edge} = {c} and not {b}.prev",
            f"{b}.prev = {c}",
            f"{v} = {lo} | {hi} << 8",
            f"{carry} = False",
            f"if {clear}: {v} = {0 if up else self.preset}",
            f"elif {edge}:",
            f"    {v} {'+' if up else '-'}= 1",
            f"    if {v} {'> 65535' if up else '< 0'}: {v} &= 65535; {carry} = True",
            f"{lo} = {v} & 255; {hi} = {v} >> 8",
        )
        self.run.flag_write(f"aS[0] = (5 if {v} == 0 else 0) | (6 if {carry} else 0)")
        return [Level(v), Level(carry, True)]

    def cnt(self, up: str, down: str, clear: str) -> list[Level]:
        b, lo, hi = self.b, self.lo, self.hi
        u, d, ru, rd, v, upc, downc = (self.name() for _ in range(7))
        self.emit(
            f"{u} = {up} != 0; {d} = {down} != 0",
            f"{ru} = {u} and not {b}.prev; {rd} = {d} and not {b}.prev2",
            f"{b}.prev = {u}; {b}.prev2 = {d}",
            f"{v} = {lo} | {hi} << 8",
            f"{upc} = {downc} = False",
            f"if {clear}: {v} = 0",
            f"elif {ru} and not {rd}:",
            f"    {v} += 1",
            f"    if {v} > 65535: {v} = 0; {upc} = True",
            f"elif {rd} and not {ru}:",
            f"    {v} -= 1",
            f"    if {v} < 0: {v} = 65535; {downc} = True",
            f"{lo} = {v} & 255; {hi} = {v} >> 8",
        )
        self.run.flag_write(f"aS[0] = (5 if {v} == 0 else 0) | (6 if {upc} or {downc} else 0)")
        return [Level(v), Level(upc, True), Level(downc, True)]

    def shift(self, clock: str, serial: str) -> list[Level]:
        left = self.instr.mnemonic == "SFL"
        b, lo, hi = self.b, self.lo, self.hi
        c, edge, v, out = self.name(), self.name(), self.name(), self.name()
        if left:
            step = f"{v} = {v} << 1 & 65535 | (1 if {serial} else 0)"
        else:
            step = f"{v} = {v} >> 1 | (32768 if {serial} else 0)"
        self.emit(
            f"{c} = {clock} != 0",
            f"{edge} = {c} and not {b}.prev",
            f"{b}.prev = {c}",
            f"{v} = {lo} | {hi} << 8",
            f"{out} = False",
            f"if {edge}:",
            f"    {out} = {v} & {32768 if left else 1}",
            f"    {step}",
            f"    {lo} = {v} & 255; {hi} = {v} >> 8",
        )
        return [Level(v), Level(out, True)]

    # -- timers -------------------------------------------------------------------------------------

    def units(self, indent: str, count: str = "") -> str:
        """``units()`` of the timer's clock: the name holding the whole units to add."""
        b, unit = self.b, TIME_BASES_NS[self.instr.arg.code]
        ran, passed = self.name(), self.name()
        self.emit(
            f"{indent}{ran} = {b}.last_pass == m.pass_no - 1",
            f"{indent}{b}.last_pass = m.pass_no",
            f"{indent}if {count}{b}.timing and {ran}:",
        )
        if self.per_timer:
            acc = self.name()
            self.emit(
                f"{indent}    {acc} = {b}.acc + m.t0 - m.prev_t0",
                f"{indent}    {b}.acc = {acc} % {unit}; {passed} = {acc} // {unit}",
            )
        else:
            self.emit(f"{indent}    {passed} = m.t0 // {unit} - m.prev_t0 // {unit}")
        self.emit(f"{indent}else: {passed} = 0")
        return passed

    def clear(self, indent: str) -> None:
        self.emit(f"{indent}{self.lo} = {self.hi} = 0; {self.b}.acc = 0; {self.b}.overflow = False")
        self.run.flag_write(f"{indent}aS[0] = 0")

    def advance(self, indent: str, passed: str, value: str, over: str) -> None:
        b, lo, hi = self.b, self.lo, self.hi
        self.emit(
            f"{indent}{value} = {lo} | {hi} << 8; {over} = False",
            f"{indent}if {passed}:",
            f"{indent}    {value} += {passed}",
            f"{indent}    if {value} >= {self.top}:",
            f"{indent}        {value} = {self.top}; {over} = not {b}.overflow; {b}.overflow = True",
            f"{indent}    {lo} = {value} & 255; {hi} = {value} >> 8",
        )

    def flags(self, indent: str, preset: str, value: str, over: str) -> None:
        p, v, b = preset, value, self.b
        self.run.flag_write(f"{indent}aS[0] = {_relation_flags(p, v)} | {b}.overflow << 4 | {over} << 5")

    def ton(self, xt: str, preset: str) -> list[Level]:
        b, v, over, out = self.b, self.name(), self.name(), self.name()
        self.emit(f"if not {xt}:", f"    {b}.last_pass = m.pass_no; {b}.timing = False")
        self.clear("    ")
        self.emit(f"    {out} = False", "else:")
        passed = self.units("    ")
        self.emit(f"    if not {b}.timing:")
        self.clear("        ")
        self.emit(f"        {b}.timing = True; {passed} = 0")
        self.advance("    ", passed, v, over)
        self.flags("    ", preset, v, over)
        self.emit(f"    {out} = {v} >= {preset}")
        return [Level(out, True)]

    def tof(self, xt: str, preset: str) -> list[Level]:
        b, v, over, out, falling = self.b, self.name(), self.name(), self.name(), self.name()
        self.emit(f"if {xt}:", f"    {b}.last_pass = m.pass_no; {b}.prev = True; {b}.timing = False")
        self.clear("    ")
        self.emit(f"    {out} = True", "else:")
        passed = self.units("    ")
        self.emit(f"    {falling} = {b}.prev; {b}.prev = False", f"    if {falling}:")
        self.clear("        ")
        self.emit(f"        {b}.timing = True; {passed} = 0", f"    if not {b}.timing: {out} = False", "    else:")
        self.advance("        ", passed, v, over)
        self.flags("        ", preset, v, over)
        self.emit(f"        {out} = {v} < {preset}")
        return [Level(out, True)]

    def imp(self, xt: str, preset: str) -> list[Level]:
        b = self.b
        v, over, out, x, rising, going = (self.name() for _ in range(6))
        passed = self.units("")
        self.emit(
            f"{x} = {xt} != 0",
            f"{rising} = {x} and not {b}.prev",
            f"{b}.prev = {x}",
            f"{going} = True",
            f"if not {b}.timing:",
            f"    if not {rising}: {going} = False",
            "    else:",
        )
        self.clear("        ")
        self.emit(f"        {b}.timing = True; {passed} = 0", f"{out} = False", f"if {going}:")
        self.advance("    ", passed, v, over)
        self.flags("    ", preset, v, over)
        self.emit(f"    if {v} >= {preset}: {b}.timing = False", f"    else: {out} = True")
        return [Level(out, True)]

    def rto(self, xt: str, rt: str, preset: str) -> list[Level]:
        b, v, over, out, carry = self.b, self.name(), self.name(), self.name(), self.name()
        passed = self.units("", f"{xt} and not {rt} and ")
        self.emit(f"if {rt}:", f"    {b}.timing = False")
        self.clear("    ")
        self.emit(f"    {out} = {carry} = False", "else:", f"    if {xt}:", f"        if not {b}.timing: {passed} = 0")
        self.emit(f"        {b}.timing = True")
        self.advance("        ", passed, v, over)
        self.emit("    else:", f"        {b}.timing = False", f"        {v} = {self.lo} | {self.hi} << 8")
        self.emit(f"        {over} = False")
        self.flags("    ", preset, v, over)
        self.emit(f"    {out} = {v} >= {preset}; {carry} = {b}.overflow")
        return [Level(out, True), Level(carry, True)]
