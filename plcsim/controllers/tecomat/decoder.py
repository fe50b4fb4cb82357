"""The assembler's last step: each instruction's operand text decoded and checked against what it takes.

Once pass 1 (:mod:`.assembler`) has read the lines into raw statements (:class:`Raw`) and declared the
program's names, registers and tables, :class:`Decoder` turns each statement's text into its argument: an
operand, a name or a constant expression (``low``/``high`` of a word), a label, a timer ``RWn.code``, a
table, a parameter (``POP 2``, ``CHG B``). :data:`OPERANDS` says, after the manual's operand lists, which
areas and widths each instruction takes; an argument outside them is an :class:`AssemblyError` at the
operand's column. Last it checks that jumps stay in their process and calls go to P60.
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from typing import Any

from plcsim.controllers.tecomat.assembly import Assembly, AssemblyError, Instruction, Label, Table, Timer
from plcsim.controllers.tecomat.memory import SIZE, Operand, OperandError, immediate, low_high, parse_address
from plcsim.controllers.tecomat.mnemonics import WITHOUT_OPERAND_FORM
from plcsim.controllers.tecomat.numbers import NumberError, expression
from plcsim.core.errors import did_you_mean


@dataclass
class Raw:
    """One statement as pass 1 read it: the mnemonic, its operand text and where both are written."""

    mnemonic: str
    text: str
    line: int
    column: int
    op_column: int
    process: int


class Decoder:
    """Decodes the raw statements of one program into its :attr:`Assembly.code`."""

    def __init__(self, asm: Assembly, r_size: int):
        self.asm, self.filename, self.r_size = asm, asm.filename, r_size

    def fail(self, line: int, column: int, message: str) -> AssemblyError:
        """The error at ``line``, ``column`` of the program (the caller raises it)."""
        return AssemblyError(f"{self.filename}, line {line}, column {column}: {message}")

    def parameter(self, lineno: int, column: int, text: str, what: str, lo: int, hi: int) -> int:
        """A number ``lo..hi`` written after ``what`` (``P 0``, ``L 10``, ``POP 2``)."""
        if not text.isdigit() or not lo <= int(text) <= hi:
            raise self.fail(lineno, column, f"{what} takes a number {lo}..{hi}, not {text!r}")
        return int(text)

    def decode(self, raw: list[Raw]) -> None:
        """Append each statement's instruction to the assembly, then check where jumps and calls go."""
        for r in raw:
            arg = self._argument(r)
            self.asm.code.append(Instruction(r.mnemonic, arg, r.line, r.column, r.process))
        self._check_targets()

    def operand(self, r: Raw, text: str) -> Operand:
        """An operand, a name or a constant expression (errors at the operand's column)."""
        lowered = text.lower()
        for prefix, high in (("low ", False), ("high ", True)):
            if lowered.startswith(prefix):
                try:
                    return low_high(self.operand(r, text[len(prefix) :].strip()), high)
                except OperandError as exc:
                    raise self.fail(r.line, r.op_column, str(exc)) from None
        symbol = self.asm.symbols.get(lowered)  # an I/O name spelt like an address (S1, D1) shadows it
        if symbol is not None:
            return symbol.operand if symbol.operand is not None else immediate(symbol.value)  # type: ignore[arg-type]
        try:
            return parse_address(text)
        except OperandError as exc:
            if ADDRESSLIKE.match(text):
                raise self.fail(r.line, r.op_column, str(exc)) from None
        constants = {k: s.value for k, s in self.asm.symbols.items() if s.value is not None}
        try:
            value = expression(text, constants)
        except NumberError as exc:
            if re.fullmatch(r"[^\W\d][\w]*", text):
                names = [s.name for s in self.asm.symbols.values()] + [t.name for t in self.asm.tables.values()]
                raise self.fail(
                    r.line, r.op_column, f"no name {text!r}{did_you_mean(text, names)}; declare it with #def or #reg"
                ) from None
            raise self.fail(r.line, r.op_column, str(exc)) from None
        if not 0 <= value <= 0xFFFF:
            raise self.fail(r.line, r.op_column, f"{text} = {value} does not fit 16 bits (0..65535)")
        return immediate(value)

    def _argument(self, r: Raw) -> Any:
        m, text = r.mnemonic, r.text
        spec = OPERANDS.get(m)
        if spec is None:  # no operand, or a parameter
            return self._parameter_argument(r)
        if not text:
            if m in WITHOUT_OPERAND_FORM:
                return None
            raise self.fail(r.line, r.op_column, f"{m} needs an operand ({spec.describe()})")
        if spec.kind == "label":
            return self._label(r, text)
        if spec.kind == "table":
            return self._table_arg(r, text, spec)
        if spec.kind == "timer":
            return self._timer(r, text)
        operand = self.operand(r, text)
        spec.check(self, r, operand)
        return operand

    def _parameter_argument(self, r: Raw) -> Any:
        m, text = r.mnemonic, r.text
        if m in ("POP", "BP", "L", "E", "CHG"):
            if m == "CHG":
                key = text.upper()
                if key not in STACK_NAMES:
                    raise self.fail(r.line, r.op_column, f"CHG takes a stack A..H (or AS..HS), not {text!r}")
                return key
            lo, hi = {"POP": (1, 7), "BP": (0, 7), "L": (0, 255), "E": (0, 64)}[m]
            return self.parameter(r.line, r.op_column, text, m, lo, hi)
        if text:
            raise self.fail(r.line, r.op_column, f"{m} takes no operand (remove {text!r})")
        return None

    def _label(self, r: Raw, text: str) -> Label:
        compact = text.replace(" ", "")
        key = compact.upper() if re.fullmatch(r"[Ll]\d+", compact) else text.lower()
        if key not in self.asm.labels:
            names = [n for n in self.asm.labels]
            raise self.fail(r.line, r.op_column, f"no label {text!r}{did_you_mean(key, names)}")
        return Label(key)

    def _timer(self, r: Raw, text: str) -> Timer:
        base, dot, code_text = text.rpartition(".")
        if not dot:
            base, code_text = text, "0"
        word = self.operand(r, base.strip())
        _check_pair(self, r, word, r.mnemonic)
        constants = {k: s.value for k, s in self.asm.symbols.items() if s.value is not None}
        try:
            code = expression(code_text, constants)
        except NumberError:
            raise self.fail(
                r.line, r.op_column, f"the time base {code_text!r} is not 0..3 (10 ms, 100 ms, 1 s, 10 s)"
            ) from None
        if not 0 <= code <= 3:
            raise self.fail(r.line, r.op_column, f"the time base {code} is not 0..3 (10 ms, 100 ms, 1 s, 10 s)")
        return Timer(word, code)

    def _table_arg(self, r: Raw, text: str, spec: OperandSpec) -> Table | Operand:
        table = self.asm.tables.get(text.lower())
        if table is not None:
            if r.mnemonic == "FTB" and table.fmt == "bit":
                raise self.fail(r.line, r.op_column, f"FTB searches byte and word tables; {table.name} is a bit table")
            if r.mnemonic in ("LMS", "WMS") and table.fmt != "word":
                raise self.fail(
                    r.line, r.op_column, f"{r.mnemonic} works on word tables; {table.name} is a {table.fmt} table"
                )
            return table
        if r.mnemonic in ("LMS", "WMS"):
            names = [t.name for t in self.asm.tables.values()]
            raise self.fail(
                r.line, r.op_column, f"no table {text!r}{did_you_mean(text, names)}; declare it with #table word"
            )
        try:
            operand = self.operand(r, text)
        except AssemblyError:
            names = [t.name for t in self.asm.tables.values()]
            raise self.fail(
                r.line, r.op_column, f"no table {text!r}{did_you_mean(text, names)}; declare it with #table"
            ) from None
        if operand.area != "R" or operand.width == "long" or (r.mnemonic == "FTB" and operand.width == "bit"):
            raise self.fail(
                r.line, r.op_column, f"{r.mnemonic} takes a table name or a table in R (its first item), not {text}"
            )
        return operand

    def _check_targets(self) -> None:
        asm = self.asm
        for instr in asm.code:
            if not isinstance(instr.arg, Label):
                continue
            target = asm.label_process[instr.arg.name]
            if instr.mnemonic.startswith("CA"):
                if target != 60:
                    raise self.fail(
                        instr.line,
                        instr.column,
                        f"{instr.mnemonic} {instr.arg}: subroutines live in process P60, the label is in P{target}",
                    )
            elif target != instr.process:
                raise self.fail(
                    instr.line,
                    instr.column,
                    f"{instr.mnemonic} {instr.arg}: a jump stays in its process (P{instr.process}); "
                    f"the label is in P{target}",
                )
        seen: dict[tuple[str, int], int] = {}
        for instr in asm.code:
            if instr.mnemonic in ("TON", "TOF", "RTO", "IMP"):
                key = ("timer", instr.arg.word.index)
            elif instr.mnemonic in ("CTU", "CTD", "CNT"):
                key = ("counter", instr.arg.index)
            else:
                continue
            if key in seen and key[0] == "timer":
                asm.warnings.append(
                    f"{self.filename}, line {instr.line}: a second timer instruction on RW{key[1]} (first on line "
                    f"{seen[key]}); the manual allows only one timer instruction per object"
                )
            seen.setdefault(key, instr.line)


ADDRESSLIKE = re.compile(r"^[XYSRDU]\s*[WL]?\s*\d+(\.\d+)?$", re.IGNORECASE)
"""Text that is meant as an address (``R 10``, ``xw2.1``): an error in it is told as such, not as an unknown name."""
STACK_NAMES = frozenset([*"ABCDEFGH", *(f"{c}S" for c in "ABCDEFGH")])


@dataclass(frozen=True)
class OperandSpec:
    """What an instruction's operand may be: its areas and widths (as the manual's operand lists)."""

    kind: str
    areas: str = ""
    widths: tuple[str, ...] = ()
    immediate: bool = False

    def describe(self) -> str:
        if self.kind != "operand":
            return {"label": "a label", "table": "a table", "timer": "a timer RWn.code"}[self.kind]
        return f"{'/'.join(self.widths)} of {', '.join(self.areas)}" + (" or a number" if self.immediate else "")

    def check(self, decoder: Decoder, r: Raw, op: Operand) -> None:
        if op.is_immediate:
            if not self.immediate:
                raise decoder.fail(
                    r.line, r.op_column, f"{r.mnemonic} does not take a number; it takes {self.describe()}"
                )
            return
        if op.area not in self.areas:
            raise decoder.fail(
                r.line, r.op_column, f"{r.mnemonic} does not take {op} (area {op.area}); it takes {self.describe()}"
            )
        if op.width not in self.widths:
            extra = {
                "word": " (a word operand is in the extended set)",
                "long": " (in the extended set only LD, LDC, WR, WRC and PUT take a long)",
            }.get(op.width, "")
            raise decoder.fail(
                r.line, r.op_column, f"{r.mnemonic} {op}: a {op.width} operand is not allowed{extra}; {self.describe()}"
            )
        if self.kind == "pair":
            _check_pair(decoder, r, op, r.mnemonic)
        size = {"X": 128, "Y": 128, "S": 64, "R": decoder.r_size, "U": 128, "D": len(decoder.asm.data)}[op.area]
        if op.index + SIZE[op.width] - 1 >= size:
            raise decoder.fail(r.line, r.op_column, f"{op} is outside {op.area}0..{op.area}{size - 1}")


def _check_pair(decoder: Decoder, r: Raw, op: Operand, mnemonic: str) -> None:
    if op.is_immediate or op.area != "R" or op.width != "word" or op.index > 254:
        raise decoder.fail(r.line, r.op_column, f"{mnemonic} works on a register pair RW0..RW254, not {op}")


_READ = OperandSpec("operand", "XYSRD", ("bit", "byte", "word", "long"), True)
_WRITE = OperandSpec("operand", "XYSR", ("bit", "byte", "word", "long"))
_LOGIC = OperandSpec("operand", "XYSRUD", ("bit", "byte"), True)
_MEMORY = OperandSpec("operand", "XYSR", ("bit", "byte"))
_COMPARE = OperandSpec("operand", "XYSRD", ("byte", "word"), True)
_PAIR = OperandSpec("pair", "R", ("word",))
OPERANDS: dict[str, OperandSpec] = {
    **dict.fromkeys(("LD", "LDC"), _READ),
    **dict.fromkeys(("WR", "WRC", "PUT"), _WRITE),
    **dict.fromkeys(("AND", "ANC", "OR", "ORC", "XOR", "XOC"), _LOGIC),
    **dict.fromkeys(("SET", "RES", "LET"), _MEMORY),
    **dict.fromkeys(("EQ", "LT", "GT", "ADD"), _COMPARE),
    **dict.fromkeys(("CTU", "CTD", "CNT", "SFL", "SFR"), _PAIR),
    **dict.fromkeys(("TON", "TOF", "RTO", "IMP"), OperandSpec("timer")),
    **dict.fromkeys(("JMP", "JMD", "JMC", "CAL", "CAD", "CAC"), OperandSpec("label")),
    **dict.fromkeys(("LTB", "FTB", "LMS", "WMS"), OperandSpec("table")),
}
