"""A ``.mech`` program linked into the S7 runtime: one cyclic task, the file run top to bottom each scan.

Each ``MECH_BEGIN .. MECH_END`` is a network driving a MECHANISM instance of the mechanism's name (the
same instance type the Python form declares, :mod:`plcsim.controllers.s7.instructions.mechanisms`); the
code between mechanisms is a network too. The instruction list is decoded once, when the program is
linked, into tuples a small interpreter walks: RLO and DR are its registers, ``DS`` areas are bytes of
the program's own (little-endian words; the chapter does not say).

Names: a tag of the I/O table; a mechanism's name (its activation bit), ``NAME_LINE`` (its
``LINE``); an ``EQUI`` constant; ``(AREA+n)`` in a ``DS`` area. A name that ``WR``/``FL`` (a Bool) or
``STO`` (an Int) writes and that nothing declares becomes a memory cell of the program (the chapter
declares its cells elsewhere); a name only read and declared nowhere is an error with the nearest names.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

from plcsim.controllers.loaded import (
    LinkTarget,
    LoadedNetwork,
    LoadedProgram,
    LoadedTask,
    NetworkSpec,
    ProgramFacts,
    TaskSpec,
)
from plcsim.controllers.plc836.grammar import STATES, address, number, split_typed
from plcsim.controllers.s7.instructions import FB_TYPES
from plcsim.core.errors import ProgramError, ProgramFileError, UnknownTagError, did_you_mean
from plcsim.frontends.mech.codegen import (
    BIT,
    CELL,
    CONST,
    END,
    FL,
    INIT,
    JUM,
    LA,
    LDR,
    LINE,
    LO,
    LOD,
    STATE,
    STO,
    TAG,
    WR,
    compile_functions,
    segment_lines,
)
from plcsim.frontends.mech.parse import Instruction, MechSource, parse
from plcsim.tags.table import TagTable
from plcsim.tags.types import Bool, ElementaryType, Int


class MechProgram:
    """A ``.mech`` program as read: declares its mechanisms and memory cells, links into the S7 runtime."""

    def __init__(self, text: str, filename: str = "<mech>"):
        self.filename, self.text = filename, text
        self.source: MechSource = parse(text, filename)
        self._order = self._declared_names()

    @classmethod
    def from_file(cls, path: str | Path) -> MechProgram:
        path = Path(path)
        try:
            text = path.read_text(encoding="utf-8")
        except UnicodeDecodeError:
            text = path.read_text(encoding="cp1250")
        except OSError as exc:
            raise ProgramFileError(f"{path}: cannot read the program: {exc.strerror}") from None
        return cls(text, str(path))

    # -- declarations --------------------------------------------------------------------------

    def _declared_names(self) -> list[tuple[str, str]]:
        """(name, kind) of what the program declares itself, by first mention: ``mechanism``, ``bit``, ``int``."""
        src = self.source
        written: dict[str, str] = {}
        for ins in src.body:
            if ins.op in ("WR", "FL"):
                written.setdefault(ins.args[-1].lstrip("-"), "bit")
            elif ins.op == "STO" and address(split_typed(ins.args[0])[1]) is None:
                written.setdefault(ins.args[0], "int")
        order: list[tuple[str, str]] = []
        seen: set[str] = set()
        for ins in src.body:
            for arg in ins.args:
                name = arg.lstrip("-")
                if name in seen:
                    continue
                if name in src.mechanisms:
                    order.append((name, "mechanism"))
                    seen.add(name)
                elif name in written and name not in src.constants and name not in src.areas:
                    order.append((name, written[name]))
                    seen.add(name)
        return order

    def declare_into(self, table: TagTable) -> TagTable:
        merged = table.copy()
        for name, kind in self._order:
            if name in merged:
                if kind == "mechanism" and block_of_type(merged, name) != "MECHANISM":
                    raise ProgramError(
                        f"{self.filename}: mechanism {name} has the name of a tag of the I/O table; rename it"
                    )
                continue
            decl = FB_TYPES["MECHANISM"]() if kind == "mechanism" else Bool if kind == "bit" else Int
            merged.add(name, decl, source=self.filename)
        return merged

    def absolute_addresses(self) -> list[str]:
        return []

    # -- linking -------------------------------------------------------------------------------

    def link(self, target: LinkTarget) -> LoadedProgram:
        linker = _Linker(self.source, target)
        segments = linker.segments()
        cells = {id(data): f"area_{name}" for name, data in linker.areas.items()}
        direct = frozenset(linker.bools - target.aliased)
        bodies = [segment_lines(linker.decode(first, end, mech), mech, direct, cells) for first, end, mech in segments]
        namespace: dict[str, Any] = {"store": target.hooks.store, "tick": target.hooks.tick, "regs": linker.regs}
        namespace["counters"] = linker.counters
        namespace.update({cells[id(data)]: data for data in linker.areas.values()})
        runs, whole = compile_functions(bodies, namespace, self.filename)
        networks, specs = [], []
        for k, ((first, last, mech), run) in enumerate(zip(segments, runs, strict=True), 1):
            lines = (self.source.body[first].line, self.source.body[last - 1].line)
            networks.append(LoadedNetwork(run, lines))
            title = f"mechanism {mech}" if mech else "logic"
            specs.append(NetworkSpec(mech or f"network_{k}", title, None, lines[0]))
        spec = TaskSpec("OB1", "cyclic", specs, number=1)
        facts = ProgramFacts(
            frozenset(linker.reads), frozenset(linker.writes), frozenset(i.op for i in self.source.body)
        )
        task = LoadedTask(spec, networks, whole, facts.tags_read | facts.tags_written)
        return LoadedProgram(self.filename, [task], facts)


def block_of_type(table: TagTable, name: str) -> str | None:
    member_type = table[name].member.type
    return getattr(member_type, "name", None)


class _Linker:
    """Decodes the instructions against one CPU's tags into the interpreter's tuples."""

    def __init__(self, source: MechSource, target: LinkTarget):
        self.src, self.target = source, target
        self.file = source.filename
        self.reads: set[str] = set()
        self.writes: set[str] = set()
        self.areas = {name: bytearray(size) for name, size in source.areas.items()}
        self.regs = [False, 0]  # RLO, DR: the CPU's registers, shared by every network
        self.counters: dict[str, list[int]] = {}
        """The named counters (``citac``) of the timed states, each ``[start ns]``, shared by every state
        that names it; ``-`` or ``NIL`` gives a state a timer of its own."""
        known = target.table.entries
        self.bools = {
            n for n, e in known.items() if isinstance(e.member.type, ElementaryType) and e.member.type is Bool
        }
        self.values = {n for n, e in known.items() if isinstance(e.member.type, ElementaryType)}

    def fail(self, ins: Instruction, message: str) -> ProgramError:
        return ProgramError(f"{self.file}, line {ins.line}: {message}")

    def segments(self) -> list[tuple[int, int, str | None]]:
        """(first, end, mechanism or None) of each network, in program order (``end`` exclusive)."""
        spans = sorted((m.begin, m.end, m.name) for m in self.src.mechanisms.values())
        out: list[tuple[int, int, str | None]] = []
        pc = 0
        for begin, end, name in spans:
            if pc < begin:
                out.append((pc, begin, None))
            out.append((begin, end + 1, name))
            pc = end + 1
        if pc < len(self.src.body):
            out.append((pc, len(self.src.body), None))
        return out

    # -- operands ----------------------------------------------------------------------------

    def unknown(self, ins: Instruction, name: str, what: str) -> UnknownTagError:
        candidates = [*self.target.table.entries, *self.src.constants, *self.src.mechanisms]
        return UnknownTagError(
            f"{self.file}, line {ins.line}: no {what} {name!r}{did_you_mean(name, candidates)}; declare it in "
            f"the I/O table, write it in the program (WR/FL/STO declare a memory cell) or fix the name"
        )

    def bit(self, ins: Instruction, arg: str, *, write: bool = False) -> tuple[int, Any, bool]:
        negate = arg.startswith("-")
        name = arg[1:] if negate else arg
        if write and negate:
            raise self.fail(ins, f"{ins.op} writes a bit; write {ins.op} {name} (a '-' negates only a read)")
        if name in self.src.mechanisms:
            (self.writes if write else self.reads).add(name)
            return BIT, name, negate
        if name in self.bools:
            (self.writes if write else self.reads).add(name)
            return TAG, name, negate
        if name in self.values:
            raise self.fail(ins, f"{name} is a number, not a bit; {ins.op} reads and writes bits (use LOD/STO)")
        raise self.unknown(ins, name, "bit")

    def cell(self, ins: Instruction, arg: str) -> tuple[int, Any, Any]:
        """A DS cell: (CELL, (bytes, offset), width) from ``BYTE.(A+n)`` / ``WORD.(A+n)`` / ``(A+n)``."""
        kind, rest = split_typed(arg)
        where = address(rest)
        if where is None:
            raise self.fail(ins, f"{arg!r} is not an address; write (AREA+n), BYTE.(AREA+n) or WORD.(AREA+n)")
        area, offset = where
        if area not in self.areas:
            raise self.unknown(ins, area, "DS area")
        width = 1 if kind == "BYTE" else 2
        if offset + width > len(self.areas[area]):
            raise self.fail(ins, f"({area}+{offset}) lies outside {area}: DS {len(self.areas[area])}")
        return CELL, (self.areas[area], offset), width

    def value(self, ins: Instruction, arg: str) -> tuple[int, Any, Any]:
        """A value operand (LOD, a TEX/TIM time): a constant, a tag, NAME_LINE or a DS cell."""
        found = number(arg)
        if found is not None:
            return CONST, found, None
        if arg in self.src.constants:
            return CONST, self.src.constants[arg], None
        if split_typed(arg)[0] is not None or arg.startswith("("):
            return self.cell(ins, arg)
        if arg.endswith("_LINE") and arg[:-5] in self.src.mechanisms:
            self.reads.add(arg[:-5])
            return LINE, arg[:-5], None
        if arg in self.values:
            self.reads.add(arg)
            return TAG, arg, None
        raise self.unknown(ins, arg, "value")

    # -- decoding ----------------------------------------------------------------------------

    def decode(self, first: int, end: int, mech: str | None) -> list[tuple[Any, ...]]:
        body, ops = self.src.body, []
        states = {line: k for k, line in enumerate(self.src.mechanisms[mech].states, 1)} if mech else {}
        for pc in range(first, end):
            ins = body[pc]
            op, args = ins.op, ins.args
            if op in ("LDR", "LO", "LA"):
                ops.append(({"LDR": LDR, "LO": LO, "LA": LA}[op], *self.bit(ins, args[0])))
            elif op == "WR":
                ops.append((WR, *self.bit(ins, args[0], write=True)))
            elif op == "FL":
                if args[0] not in ("0", "1"):
                    raise self.fail(ins, f"FL sets a bit to 0 or 1: write FL 1,{args[1]} or FL 0,{args[1]}")
                ops.append((FL, *self.bit(ins, args[1], write=True), args[0] == "1"))
            elif op == "LOD":
                ops.append((LOD, *self.value(ins, args[0])))
            elif op == "STO":
                ops.append((STO, *self.store_target(ins, args[0])))
            elif op == "JUM":
                ops.append((JUM, self.jump(ins, args[0], first, end), ins.line))
            elif op == "MECH_INIT":
                if args[0] not in self.src.mechanisms:
                    raise self.unknown(ins, args[0], "mechanism")
                self.writes.add(args[0])
                ops.append((INIT, args[0]))
            elif op in STATES:
                ops.append(self.state(ins, states[ins.line], first, end))
            elif op == "MECH_END":
                ops.append((END,))
            elif op == "MECH_BEGIN":
                ops.append((END,))  # never executed: a mechanism's network starts after it
            else:  # pragma: no cover - the parser admits no other mnemonic
                raise self.fail(ins, f"{op} cannot be linked")
        return ops

    def store_target(self, ins: Instruction, arg: str) -> tuple[int, Any, Any]:
        if split_typed(arg)[0] is not None or arg.startswith("("):
            return self.cell(ins, arg)
        if arg in self.values and arg not in self.bools:
            self.writes.add(arg)
            return TAG, arg, None
        if arg in self.bools:
            raise self.fail(ins, f"STO stores the number in DR; {arg} is a bit (use WR or FL)")
        raise self.unknown(ins, arg, "number cell")

    def jump(self, ins: Instruction, label: str, first: int, end: int) -> int:
        where = self.src.labels.get(label)
        if where is None:
            raise self.fail(
                ins, f"no label {label}{did_you_mean(label, self.src.labels)}; write '{label}:' before an instruction"
            )
        if not first <= where < end or self.src.body[where].op == "MECH_BEGIN":
            place = "this mechanism" if self.src.body[first].op == "MECH_BEGIN" else "the code outside mechanisms"
            raise self.fail(ins, f"label {label} lies outside {place}; a jump stays inside it")
        return where - first

    def state(self, ins: Instruction, n: int, first: int, end: int) -> tuple[Any, ...]:
        op, args = ins.op, ins.args
        kind = {"TEX0": "EX0", "TEX1": "EX1"}.get(op, op)
        limit: tuple[Any, ...] = (None, None, None)
        label_pc, label, code, counter = -1, "", None, None
        if op in ("TEX0", "TEX1", "TIM"):
            typed, written = split_typed(args[0])
            if written.upper() not in ("-", "NIL"):
                where = address(written)
                counter = written if where is None else f"{where[0]}+{where[1]}"
                self.counters.setdefault(counter, [0])
            time_arg = args[1]
            if typed is not None:
                time_arg = f"{typed}.{time_arg}"
            limit = self.value(ins, time_arg)
            if op != "TIM":
                label_pc, label = self.jump(ins, args[2], first, end), args[2]
                if len(args) == 4:
                    code = number(args[3]) if args[3] not in self.src.constants else self.src.constants[args[3]]
                    if code is None:
                        raise self.fail(ins, f"the error number {args[3]!r} must be a number such as 04 or 12H")
        return (STATE, kind, n, ins.line, *limit, label_pc, label, code, counter)


def read_mech(path: Path) -> MechProgram:
    """The ``.mech`` front end's reader (:func:`plcsim.frontends.register`)."""
    return MechProgram.from_file(path)


__all__ = ["MechProgram", "read_mech"]
