"""The ``.il`` assembler: the manual's source syntax, read once into decoded instructions.

Syntax as in the manual's listings (case-insensitive mnemonics, operands and names): one instruction a
line, ``;`` starts a comment; ``name:`` (or ``#label name``) and ``L n`` are labels; directives
``#program``, ``#def name operand-or-constant``, ``#reg word|byte|bit name[, name...]`` (``name[n]``
reserves n items), ``#table bit|byte|word name = items`` (``0[5]`` repeats), ``#data byte|word name =
items`` (the read-only area D; the manual gives it no syntax, this is ours), ``#include``/``#unit``
(ignored with a warning: the rig wires X and Y). Processes are bracketed ``P n`` ... ``E n``; a file
without any ``P`` is process P0 as a whole (EX-01 is printed so).

Errors name the file, the line and the column and suggest the nearest mnemonic or name.

>>> asm = assemble("#def START x0.0\\n#def MOTOR y0.0\\nLD START\\nWR MOTOR\\n", "motor.il")
>>> [(i.mnemonic, str(i.arg), i.line) for i in asm.code]
[('LD', 'X0.0', 3), ('WR', 'Y0.0', 4), ('E', '0', 4)]
>>> assemble("LD X0.0\\nWX Y0.0\\n", "bad.il")
Traceback (most recent call last):
...
plcsim.controllers.tecomat.assembler.AssemblyError: bad.il, line 2, column 1: no instruction 'WX'; did you mean WR?
"""

from __future__ import annotations

import difflib
import re
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

from plcsim.controllers.tecomat.memory import SIZE, Operand, OperandError, immediate, low_high, parse_address
from plcsim.controllers.tecomat.mnemonics import DEFINED, NAMED_ONLY, WITHOUT_OPERAND_FORM, refusal
from plcsim.controllers.tecomat.numbers import NumberError, expression
from plcsim.core.errors import ProgramError, did_you_mean

MAX_LINE = 1000
"""Longest source line (the manual's are short; a longer one is a mistake or an attack on the grader)."""
MAX_DATA = 65_536
"""Most bytes of program data (#data) one program may declare."""
PROCESSES = frozenset([*range(0, 49), *range(50, 58), 60, 62, 63, 64])
TABLE_MAX = {"bit": 256, "byte": 256, "word": 128}
ITEM_MAX = {"bit": 1, "byte": 0xFF, "word": 0xFFFF}
_NAME = re.compile(r"^[^\W\d]\w*$")
_LABEL = re.compile(r"^([^\W\d]\w*)\s*:\s*(.*)$")
_ITEM = re.compile(r"^(.*?)\s*\[\s*(\d+)\s*\]$")


class AssemblyError(ProgramError):
    """A program the assembler cannot read: the message starts with ``file, line n, column c``."""


@dataclass(frozen=True)
class Timer:
    """A timer operand ``word.code``: the register pair and the time base (0..3)."""

    word: Operand
    code: int

    def __str__(self) -> str:
        return f"{self.word}.{self.code}"


@dataclass(frozen=True)
class Label:
    """A jump target: a named label (``konec``) or a numbered one (``L 10``)."""

    name: str

    def __str__(self) -> str:
        return self.name


@dataclass
class Table:
    """A table in T (``#table``): its format, items and number (declaration order, from 0)."""

    name: str
    fmt: str
    items: list[int]
    number: int
    line: int

    @property
    def limit(self) -> int:
        return len(self.items) - 1

    def layout(self) -> bytes:
        """The table's bytes as the manual draws them: bits LSB first, words little-endian."""
        if self.fmt == "bit":
            out = bytearray((len(self.items) + 7) // 8)
            for i, item in enumerate(self.items):
                out[i // 8] |= item << (i % 8)
            return bytes(out)
        if self.fmt == "byte":
            return bytes(self.items)
        return b"".join(item.to_bytes(2, "little") for item in self.items)


@dataclass
class Symbol:
    """A name the program declares: an operand (``#def``/``#reg``/``#data``) or a constant (``#def``)."""

    name: str
    operand: Operand | None
    value: int | None
    line: int
    directive: str


@dataclass
class Instruction:
    """One decoded instruction: mnemonic, argument, where it is written and in which process."""

    mnemonic: str
    arg: Any
    line: int
    column: int
    process: int


@dataclass
class Assembly:
    """A whole program, decoded: its instructions, processes, labels, names and tables."""

    filename: str
    name: str = ""
    code: list[Instruction] = field(default_factory=list)
    processes: dict[int, int] = field(default_factory=dict)
    """Process number -> index of its first instruction."""
    labels: dict[str, int] = field(default_factory=dict)
    """Label (``konec``, ``L10``) -> index of the instruction it marks."""
    label_process: dict[str, int] = field(default_factory=dict)
    symbols: dict[str, Symbol] = field(default_factory=dict)
    """Lower-case name -> symbol."""
    tables: dict[str, Table] = field(default_factory=dict)
    data: bytes = b""
    warnings: list[str] = field(default_factory=list)

    def where(self, index: int) -> str:
        """``file, line n`` of the instruction at ``index``."""
        return f"{self.filename}, line {self.code[index].line}"


@dataclass
class _Raw:
    mnemonic: str
    text: str
    line: int
    column: int
    op_column: int
    process: int


def assemble(
    source: str, filename: str = "<il>", *, r_size: int = 8192, predefined: Mapping[str, Operand] | None = None
) -> Assembly:
    """Read ``.il`` source text into an :class:`Assembly` (AssemblyError names the place and the fix).

    ``predefined`` names operands before the program does (an exercise's I/O table: ``TLACIDLO`` = X0.0);
    the program's own ``#def`` of a name replaces it."""
    return _Assembler(source, filename, r_size, predefined or {}).run()


class _Assembler:
    def __init__(self, source: str, filename: str, r_size: int, predefined: Mapping[str, Operand]):
        self.source, self.filename, self.r_size = source, filename, r_size
        self.asm = Assembly(filename)
        self.predefined = {name.lower(): operand for name, operand in predefined.items()}
        for name, operand in predefined.items():
            self.asm.symbols[name.lower()] = Symbol(name, operand, None, 0, "I/O table")
            if _ADDRESSLIKE.match(name):
                self.asm.warnings.append(
                    f"{filename}: the I/O name {name} is {operand} in this program; the address {name} is "
                    f"written with a space ({name[0]} {name[1:]})"
                )
        self.raw: list[_Raw] = []
        self.defs: dict[str, tuple[str, str, int, int]] = {}
        self.regs: list[tuple[str, str, str, int, int, int]] = []
        self.pending_labels: list[tuple[str, int, int]] = []
        self.raw_labels: dict[str, tuple[int, int, int]] = {}

    def fail(self, line: int, column: int, message: str) -> AssemblyError:
        return AssemblyError(f"{self.filename}, line {line}, column {column}: {message}")

    # -- pass 1: lines into directives, labels and raw instructions -------------------------------

    def run(self) -> Assembly:
        lines = self.source.splitlines()
        explicit = any(self._opens_process(line) for line in lines)
        self.process: int | None = None if explicit else 0
        for lineno, raw in enumerate(lines, 1):
            self._line(lineno, raw)
        if not explicit:
            self._end_process(len(lines) or 1, 1, 0)
        elif self.process is not None:
            raise self.fail(len(lines), 1, f"process P{self.process} is not closed; end it with 'E {self.process}'")
        if self.pending_labels:
            name, line, col = self.pending_labels[0]
            raise self.fail(line, col, f"the label {name} marks no instruction; put it before one")
        self._declare()
        self._decode()
        return self.asm

    @staticmethod
    def _opens_process(line: str) -> bool:
        words = line.split(";", 1)[0].split()
        return len(words) >= 2 and words[0].upper() == "P" and words[1].isdigit()

    def _line(self, lineno: int, raw: str) -> None:
        if len(raw) > MAX_LINE:
            raise self.fail(lineno, MAX_LINE, f"the line is longer than {MAX_LINE} characters; split it")
        text = raw.split(";", 1)[0].rstrip()
        stripped = text.strip()
        if not stripped:
            return
        column = len(text) - len(text.lstrip()) + 1
        if stripped.startswith("#"):
            self._directive(lineno, column, stripped)
            return
        if stripped.startswith("."):
            raise self.fail(lineno, column, "a line starting with '.' is not an instruction; comments start with ';'")
        label = _LABEL.match(stripped)
        if label:
            self._mark_label(label.group(1), lineno, column)
            rest = label.group(2)
            if not rest:
                return
            column += stripped.index(rest)
            stripped = rest
        self._statement(lineno, column, stripped)

    def _statement(self, lineno: int, column: int, text: str) -> None:
        parts = text.split(None, 1)
        mnemonic = parts[0].upper()
        rest = parts[1].strip() if len(parts) > 1 else ""
        op_column = column + (text.index(rest, len(parts[0])) if rest else len(parts[0]))
        if mnemonic in ("P", "E") and rest:
            number, _, after = rest.partition(" ")
            if number.isdigit() and after.strip():  # "p 0     ld dny_v_tydnu" (EX-21 as printed)
                self._statement(lineno, column, f"{mnemonic} {number}")
                after = after.strip()
                self._statement(lineno, op_column + rest.index(after), after)
                return
        if mnemonic in NAMED_ONLY:
            raise self.fail(lineno, column, refusal(mnemonic))
        if mnemonic not in DEFINED:
            raise self.fail(lineno, column, f"no instruction {parts[0]!r}{_nearest_mnemonic(mnemonic)}")
        if mnemonic == "P":
            self._begin_process(lineno, op_column, rest)
            return
        if mnemonic == "E":
            number = self._parameter(lineno, op_column, rest, "E", 0, 64)
            if self.process is None or number != self.process:
                which = "no process is open" if self.process is None else f"the open process is P{self.process}"
                raise self.fail(lineno, column, f"'E {number}' ends no process: {which}")
            self._end_process(lineno, column, number)
            return
        if self.process is None:
            raise self.fail(lineno, column, f"{mnemonic} is outside every process; begin one with 'P 0'")
        if mnemonic == "L":
            number = self._parameter(lineno, op_column, rest, "L", 0, 255)
            self._mark_label(f"L{number}", lineno, column)
        self._emit(mnemonic, rest, lineno, column, op_column)

    def _emit(self, mnemonic: str, text: str, lineno: int, column: int, op_column: int) -> None:
        index = len(self.raw)
        for name, line, col in self.pending_labels:
            self.asm.labels[name] = index
            self.asm.label_process[name] = self.process  # type: ignore[assignment]
            self.raw_labels[name] = (line, col, index)
        self.pending_labels = []
        self.raw.append(_Raw(mnemonic, text, lineno, column, op_column, self.process))  # type: ignore[arg-type]

    def _mark_label(self, name: str, lineno: int, column: int) -> None:
        key = name.lower() if not re.fullmatch(r"L\d+", name) else name
        if key in self.raw_labels or any(key == n for n, _, _ in self.pending_labels):
            first = self.raw_labels.get(key, (lineno, column, 0))[0]
            raise self.fail(
                lineno, column, f"the label {name} is defined twice (first on line {first}); labels are unique"
            )
        self.pending_labels.append((key, lineno, column))

    def _parameter(self, lineno: int, column: int, text: str, what: str, lo: int, hi: int) -> int:
        if not text.isdigit() or not lo <= int(text) <= hi:
            raise self.fail(lineno, column, f"{what} takes a number {lo}..{hi}, not {text!r}")
        return int(text)

    def _begin_process(self, lineno: int, column: int, text: str) -> None:
        number = self._parameter(lineno, column, text, "P", 0, 64)
        if number not in PROCESSES:
            raise self.fail(
                lineno, column, f"there is no process P{number}: the processes are P0..P48, P50..P57, P60, P62..P64"
            )
        if self.process is not None:
            raise self.fail(
                lineno, column, f"P{number} begins inside P{self.process}; end that first with 'E {self.process}'"
            )
        if number in self.asm.processes:
            raise self.fail(lineno, column, f"process P{number} is written twice")
        self.process = number
        self.asm.processes[number] = len(self.raw)

    def _end_process(self, lineno: int, column: int, number: int) -> None:
        self._emit("E", str(number), lineno, column, column)
        self.asm.processes.setdefault(number, 0)
        self.process = None

    # -- directives --------------------------------------------------------------------------------

    def _directive(self, lineno: int, column: int, text: str) -> None:
        head, _, rest = text[1:].partition(" ")
        key, rest = head.lower(), rest.strip()
        if key == "program":
            self.asm.name = rest.split(",")[0].strip()
        elif key in ("include", "unit"):
            self.asm.warnings.append(
                f"{self.filename}, line {lineno}: #{key} is ignored: the rig's wiring connects X and Y"
            )
        elif key == "def":
            name, _, value = rest.partition(" ")
            self._name(lineno, column, name)
            if not value.strip():
                raise self.fail(lineno, column, f"#def {name} needs a value: an operand (x0.0) or a constant (10)")
            self.defs[name.lower()] = (name, value.strip(), lineno, column)
        elif key == "reg":
            self._reg(lineno, column, rest)
        elif key in ("table", "data"):
            self._table(lineno, column, key, rest)
        elif key == "label":
            self._mark_label(rest, lineno, column)
        else:
            known = ["program", "include", "def", "reg", "table", "data", "unit", "label"]
            raise self.fail(lineno, column, f"no directive #{head}{did_you_mean(key, known)}")

    def _name(self, lineno: int, column: int, name: str) -> None:
        if not _NAME.match(name):
            raise self.fail(
                lineno, column, f"{name!r} is not a name (letters, digits and _, not starting with a digit)"
            )
        try:
            parse_address(name)
        except OperandError:
            pass
        else:
            raise self.fail(lineno, column, f"{name!r} is an address; a name must not look like one")
        key = name.lower()
        if key in self.defs or key in self.asm.tables or any(r[1].lower() == key for r in self.regs):
            raise self.fail(lineno, column, f"{name!r} is declared twice")

    def _reg(self, lineno: int, column: int, text: str) -> None:
        width, _, names = text.partition(" ")
        width = width.lower()
        if width not in ("bit", "byte", "word", "long"):
            raise self.fail(lineno, column, f"#reg takes bit, byte, word or long, not {width!r}")
        for item in filter(None, (n.strip() for n in names.split(","))):
            match = _ITEM.match(item)
            name, count = (match.group(1), int(match.group(2))) if match else (item, 1)
            self._name(lineno, column, name)
            if width == "bit" and count != 1:
                raise self.fail(lineno, column, "#reg bit reserves one bit; reserve a bit table as bytes")
            self.regs.append((width, name, item, count, lineno, column))

    def _table(self, lineno: int, column: int, key: str, text: str) -> None:
        width, _, body = text.partition(" ")
        width = width.lower()
        allowed = ("bit", "byte", "word") if key == "table" else ("byte", "word")
        if width not in allowed:
            raise self.fail(lineno, column, f"#{key} takes {', '.join(allowed)}, not {width!r}")
        name, eq, items = body.partition("=")
        name = name.strip()
        if not eq:
            raise self.fail(lineno, column, f"write #{key} {width} name = item, item, ...")
        self._name(lineno, column, name)
        values: list[int] = []
        limit = TABLE_MAX[width] if key == "table" else MAX_DATA // (2 if width == "word" else 1)
        for item in items.split(","):
            match = _ITEM.match(item.strip())
            text_value, repeat = (match.group(1), int(match.group(2))) if match else (item.strip(), 1)
            try:
                value = expression(text_value, {k: v for k, v in self._constants().items()})
            except NumberError as exc:
                raise self.fail(lineno, column, f"table item {item.strip()!r}: {exc}") from None
            if not 0 <= value <= ITEM_MAX[width]:
                raise self.fail(
                    lineno, column, f"table item {item.strip()!r} does not fit a {width} (0..{ITEM_MAX[width]})"
                )
            if len(values) + repeat > limit:
                raise self.fail(lineno, column, f"#{key} {name}: more than {limit} items")
            values += [value] * repeat
        if key == "data":
            offset = len(self.asm.data)
            self.asm.data += b"".join(v.to_bytes(2 if width == "word" else 1, "little") for v in values)
            self.asm.symbols[name.lower()] = Symbol(name, Operand("D", width, offset), None, lineno, "#data")
            return
        if not 1 <= len(values) <= TABLE_MAX[width]:
            raise self.fail(lineno, column, f"a {width} table has 1..{TABLE_MAX[width]} items, not {len(values)}")
        self.asm.tables[name.lower()] = Table(name, width, values, len(self.asm.tables), lineno)

    def _constants(self) -> dict[str, int]:
        out = {}
        for key, (_, value, _, _) in self.defs.items():
            try:
                out[key] = expression(value, {})
            except NumberError:
                continue
        return out

    # -- pass 2: names, registers, operands ----------------------------------------------------------

    def _declare(self) -> None:
        for key, (name, value, lineno, column) in self.defs.items():
            self.asm.symbols[key] = self._resolve_def(key, name, value, lineno, column, ())
        used = self._absolute_r()
        next_byte, next_bit = 0, None
        for width, name, _, count, lineno, column in self.regs:
            if width == "bit":
                if next_bit is None or next_bit[1] == 8:
                    next_byte = self._free(used, next_byte, 1, lineno, column)
                    next_bit = [next_byte, 0]
                    next_byte += 1
                operand = Operand("R", "bit", next_bit[0], next_bit[1])
                next_bit[1] += 1
            else:
                size = count * SIZE[width]
                start = self._free(used, next_byte, size, lineno, column)
                operand = Operand("R", width, start)
                next_byte = start + size
            self.asm.symbols[name.lower()] = Symbol(name, operand, None, lineno, "#reg")

    def _resolve_def(self, key: str, name: str, value: str, lineno: int, column: int, seen: tuple[str, ...]) -> Symbol:
        if key in seen:
            raise self.fail(lineno, column, f"#def {name} refers to itself through {' -> '.join(seen)}")
        given = self.predefined.get(value.lower())
        if given is not None:  # another name for an I/O table entry
            return Symbol(name, given, None, lineno, "#def")
        try:
            return Symbol(name, parse_address(value), None, lineno, "#def")
        except OperandError as exc:
            if _ADDRESSLIKE.match(value):
                raise self.fail(lineno, column, str(exc)) from None
        if value.lower() in self.defs and value.lower() != key:
            other = self.defs[value.lower()]
            target = self._resolve_def(value.lower(), *other, (*seen, key))
            return Symbol(name, target.operand, target.value, lineno, "#def")
        try:
            return Symbol(name, None, expression(value, self._constants()), lineno, "#def")
        except NumberError:
            raise self.fail(
                lineno, column, f"#def {name} {value}: neither an operand (x0.0, rw4) nor a constant"
            ) from None

    def _absolute_r(self) -> set[int]:
        """R bytes the program names by address (and the LMS/WMS index registers): #reg avoids them."""
        used: set[int] = set()
        texts = [r.text for r in self.raw] + [d[1] for d in self.defs.values()]
        for text in texts:
            for word in re.split(r"[\s,]+", text):
                try:
                    op = parse_address(word.split(".")[0] if word.upper().startswith("RW") else word)
                except OperandError:
                    continue
                if op.area == "R":
                    used.update(range(op.index, op.index + SIZE[op.width]))
        for r in self.raw:
            if r.mnemonic in ("LMS", "WMS") and r.text.lower() in self.asm.tables:
                number = self.asm.tables[r.text.lower()].number
                used.update((number, number + 1))
        return used

    def _free(self, used: set[int], start: int, size: int, lineno: int, column: int) -> int:
        if start + size > self.r_size:
            raise self.fail(lineno, column, f"#reg: no room left in R (R0..R{self.r_size - 1})")
        while any(b in used for b in range(start, start + size)):
            start += 1
        if start + size > self.r_size:
            raise self.fail(lineno, column, f"#reg: no room left in R (R0..R{self.r_size - 1})")
        return start

    def _decode(self) -> None:
        for r in self.raw:
            arg = self._argument(r)
            self.asm.code.append(Instruction(r.mnemonic, arg, r.line, r.column, r.process))
        self._check_targets()

    def operand(self, r: _Raw, text: str) -> Operand:
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
            if _ADDRESSLIKE.match(text):
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

    def _argument(self, r: _Raw) -> Any:
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

    def _parameter_argument(self, r: _Raw) -> Any:
        m, text = r.mnemonic, r.text
        if m in ("POP", "BP", "L", "E", "CHG"):
            if m == "CHG":
                key = text.upper()
                if key not in STACK_NAMES:
                    raise self.fail(r.line, r.op_column, f"CHG takes a stack A..H (or AS..HS), not {text!r}")
                return key
            lo, hi = {"POP": (1, 7), "BP": (0, 7), "L": (0, 255), "E": (0, 64)}[m]
            return self._parameter(r.line, r.op_column, text, m, lo, hi)
        if text:
            raise self.fail(r.line, r.op_column, f"{m} takes no operand (remove {text!r})")
        return None

    def _label(self, r: _Raw, text: str) -> Label:
        compact = text.replace(" ", "")
        key = compact.upper() if re.fullmatch(r"[Ll]\d+", compact) else text.lower()
        if key not in self.asm.labels:
            names = [n for n in self.asm.labels]
            raise self.fail(r.line, r.op_column, f"no label {text!r}{did_you_mean(key, names)}")
        return Label(key)

    def _timer(self, r: _Raw, text: str) -> Timer:
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

    def _table_arg(self, r: _Raw, text: str, spec: OperandSpec) -> Table | Operand:
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


def _nearest_mnemonic(mnemonic: str) -> str:
    near = difflib.get_close_matches(mnemonic, sorted(DEFINED), n=3, cutoff=0.5)
    return (
        f"; did you mean {' or '.join(near)}?"
        if near
        else "; the manual's instructions are listed in plcsim.controllers.tecomat.mnemonics"
    )


_ADDRESSLIKE = re.compile(r"^[XYSRDU]\s*[WL]?\s*\d+(\.\d+)?$", re.IGNORECASE)
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

    def check(self, asm: _Assembler, r: _Raw, op: Operand) -> None:
        if op.is_immediate:
            if not self.immediate:
                raise asm.fail(r.line, r.op_column, f"{r.mnemonic} does not take a number; it takes {self.describe()}")
            return
        if op.area not in self.areas:
            raise asm.fail(
                r.line, r.op_column, f"{r.mnemonic} does not take {op} (area {op.area}); it takes {self.describe()}"
            )
        if op.width not in self.widths:
            extra = {
                "word": " (a word operand is in the extended set)",
                "long": " (in the extended set only LD, LDC, WR, WRC and PUT take a long)",
            }.get(op.width, "")
            raise asm.fail(
                r.line, r.op_column, f"{r.mnemonic} {op}: a {op.width} operand is not allowed{extra}; {self.describe()}"
            )
        if self.kind == "pair":
            _check_pair(asm, r, op, r.mnemonic)
        size = {"X": 128, "Y": 128, "S": 64, "R": asm.r_size, "U": 128, "D": len(asm.asm.data)}[op.area]
        if op.index + SIZE[op.width] - 1 >= size:
            raise asm.fail(r.line, r.op_column, f"{op} is outside {op.area}0..{op.area}{size - 1}")


def _check_pair(asm: _Assembler, r: _Raw, op: Operand, mnemonic: str) -> None:
    if op.is_immediate or op.area != "R" or op.width != "word" or op.index > 254:
        raise asm.fail(r.line, r.op_column, f"{mnemonic} works on a register pair RW0..RW254, not {op}")


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
