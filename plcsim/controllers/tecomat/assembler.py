"""The ``.il`` assembler: the manual's source syntax, read once into decoded instructions.

Syntax as in the manual's listings (case-insensitive mnemonics, operands and names): one instruction a
line, ``;`` starts a comment; ``name:`` (or ``#label name``) and ``L n`` are labels; directives
``#program``, ``#def name operand-or-constant``, ``#reg word|byte|bit name[, name...]`` (``name[n]``
reserves n items), ``#table bit|byte|word name = items`` (``0[5]`` repeats), ``#data byte|word name =
items`` (the read-only area D; the manual gives it no syntax, this is ours), ``#include``/``#unit``
(ignored with a warning: the rig wires X and Y). Processes are bracketed ``P n`` ... ``E n``; a file
without any ``P`` is process P0 as a whole (EX-01 is printed so).

The assembler reads the lines (pass 1: directives, labels, processes, raw statements), declares the
names (``#def`` resolved, ``#reg`` allocated in R around the bytes the program names by address) and
hands the statements to :class:`~plcsim.controllers.tecomat.decoder.Decoder`, which decodes and checks
their operands into the :class:`~plcsim.controllers.tecomat.assembly.Assembly`. Errors name the file,
the line and the column and suggest the nearest mnemonic or name.

>>> asm = assemble("#def START x0.0\\n#def MOTOR y0.0\\nLD START\\nWR MOTOR\\n", "motor.il")
>>> [(i.mnemonic, str(i.arg), i.line) for i in asm.code]
[('LD', 'X0.0', 3), ('WR', 'Y0.0', 4), ('E', '0', 4)]
>>> assemble("LD X0.0\\nWX Y0.0\\n", "bad.il")
Traceback (most recent call last):
...
plcsim.controllers.tecomat.assembly.AssemblyError: bad.il, line 2, column 1: no instruction 'WX'; did you mean WR?
"""

from __future__ import annotations

import contextlib
import difflib
import re
from collections.abc import Mapping

from plcsim.controllers.tecomat.assembly import Assembly, AssemblyError, Symbol, Table
from plcsim.controllers.tecomat.decoder import ADDRESSLIKE, Decoder, Raw
from plcsim.controllers.tecomat.memory import SIZE, Operand, OperandError, parse_address
from plcsim.controllers.tecomat.mnemonics import DEFINED, NAMED_ONLY, refusal
from plcsim.controllers.tecomat.numbers import NumberError, expression
from plcsim.core.errors import did_you_mean

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
        self.decoder = Decoder(self.asm, r_size)
        self.predefined = {name.lower(): operand for name, operand in predefined.items()}
        for name, operand in predefined.items():
            self.asm.symbols[name.lower()] = Symbol(name, operand, None, 0, "I/O table")
            if ADDRESSLIKE.match(name):
                self.asm.warnings.append(
                    f"{filename}: the I/O name {name} is {operand} in this program; the address {name} is "
                    f"written with a space ({name[0]} {name[1:]})"
                )
        self.raw: list[Raw] = []
        self.defs: dict[str, tuple[str, str, int, int]] = {}
        self.data = bytearray()
        """The program's #data so far (grown in place: a copy per #data line would be quadratic)."""
        self.constants: dict[str, int] = {}
        """The value of each #def that is a constant, evaluated once when it is read (not for every item)."""
        self.regs: list[tuple[str, str, str, int, int, int]] = []
        self.reg_names: set[str] = set()
        self.pending_labels: list[tuple[str, int, int]] = []
        self.raw_labels: dict[str, tuple[int, int, int]] = {}

    def fail(self, line: int, column: int, message: str) -> AssemblyError:
        return self.decoder.fail(line, column, message)

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
        self.asm.data = bytes(self.data)
        self._declare()
        self.decoder.decode(self.raw)
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
            number = self.decoder.parameter(lineno, op_column, rest, "E", 0, 64)
            if self.process is None or number != self.process:
                which = "no process is open" if self.process is None else f"the open process is P{self.process}"
                raise self.fail(lineno, column, f"'E {number}' ends no process: {which}")
            self._end_process(lineno, column, number)
            return
        if self.process is None:
            raise self.fail(lineno, column, f"{mnemonic} is outside every process; begin one with 'P 0'")
        if mnemonic == "L":
            number = self.decoder.parameter(lineno, op_column, rest, "L", 0, 255)
            self._mark_label(f"L{number}", lineno, column)
        self._emit(mnemonic, rest, lineno, column, op_column)

    def _emit(self, mnemonic: str, text: str, lineno: int, column: int, op_column: int) -> None:
        index = len(self.raw)
        for name, line, col in self.pending_labels:
            self.asm.labels[name] = index
            self.asm.label_process[name] = self.process  # type: ignore[assignment]
            self.raw_labels[name] = (line, col, index)
        self.pending_labels = []
        self.raw.append(Raw(mnemonic, text, lineno, column, op_column, self.process))  # type: ignore[arg-type]

    def _mark_label(self, name: str, lineno: int, column: int) -> None:
        key = name.lower() if not re.fullmatch(r"L\d+", name) else name
        if key in self.raw_labels or any(key == n for n, _, _ in self.pending_labels):
            first = self.raw_labels.get(key, (lineno, column, 0))[0]
            raise self.fail(
                lineno, column, f"the label {name} is defined twice (first on line {first}); labels are unique"
            )
        self.pending_labels.append((key, lineno, column))

    def _begin_process(self, lineno: int, column: int, text: str) -> None:
        number = self.decoder.parameter(lineno, column, text, "P", 0, 64)
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
            with contextlib.suppress(NumberError):  # an operand or another name: resolved in pass 2
                self.constants[name.lower()] = expression(value, {})
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
        if key in self.defs or key in self.asm.tables or key in self.reg_names:
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
            self.reg_names.add(name.lower())

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
        size = 2 if width == "word" else 1
        limit = TABLE_MAX[width] if key == "table" else (MAX_DATA - len(self.data)) // size
        for item in items.split(","):
            match = _ITEM.match(item.strip())
            text_value, repeat = (match.group(1), int(match.group(2))) if match else (item.strip(), 1)
            try:
                value = expression(text_value, self.constants)
            except NumberError as exc:
                raise self.fail(lineno, column, f"table item {item.strip()!r}: {exc}") from None
            if not 0 <= value <= ITEM_MAX[width]:
                raise self.fail(
                    lineno, column, f"table item {item.strip()!r} does not fit a {width} (0..{ITEM_MAX[width]})"
                )
            if len(values) + repeat > limit:
                if key == "data" and self.data:  # MAX_DATA bounds the whole program's data
                    raise self.fail(lineno, column, f"#data {name}: the program's #data would pass {MAX_DATA} bytes")
                raise self.fail(lineno, column, f"#{key} {name}: more than {limit} items")
            values += [value] * repeat
        if key == "data":
            offset = len(self.data)
            self.data += b"".join(v.to_bytes(size, "little") for v in values)
            self.asm.symbols[name.lower()] = Symbol(name, Operand("D", width, offset), None, lineno, "#data")
            return
        if not 1 <= len(values) <= TABLE_MAX[width]:
            raise self.fail(lineno, column, f"a {width} table has 1..{TABLE_MAX[width]} items, not {len(values)}")
        self.asm.tables[name.lower()] = Table(name, width, values, len(self.asm.tables), lineno)

    # -- pass 2: names and registers (the operands are the decoder's) ---------------------------------

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
            if ADDRESSLIKE.match(value):
                raise self.fail(lineno, column, str(exc)) from None
        if value.lower() in self.defs and value.lower() != key:
            other = self.defs[value.lower()]
            target = self._resolve_def(value.lower(), *other, (*seen, key))
            return Symbol(name, target.operand, target.value, lineno, "#def")
        try:
            return Symbol(name, None, expression(value, self.constants), lineno, "#def")
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


def _nearest_mnemonic(mnemonic: str) -> str:
    near = difflib.get_close_matches(mnemonic, sorted(DEFINED), n=3, cutoff=0.5)
    return (
        f"; did you mean {' or '.join(near)}?"
        if near
        else "; the manual's instructions are listed in plcsim.controllers.tecomat.mnemonics"
    )
