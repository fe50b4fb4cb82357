"""Mutants of Tecomat instruction-list programs (``.il``): the slips students make, one line each.

:mod:`plcsim.mutate.engine` grades them like the mutants of a Python program; this module only derives them.
A mutant is the reference's text with one line changed (a swap changes two), comments and directives
kept as written except a ``#def`` constant's value; a mnemonic keeps the case it is written in
(``ld`` -> ``ldc``), as the language is case-insensitive. The operators use only the 57 instructions
the manual defines (:mod:`plcsim.controllers.tecomat.mnemonics`):

=============== ================================================================================
negate          a contact negated: LD <-> LDC, AND <-> ANC, OR <-> ORC, XOR <-> XOC, WR <-> WRC
                (an operand that is a register or a bit, not a number)
set-reset       SET <-> RES
and-or          a series connection for a parallel one: AND <-> OR, ANC <-> ORC
drop-operand    one operand of a series or parallel connection dropped, a forgotten contact: an AND, ANC, OR,
                ORC, XOR or XOC of a contact dropped, or the connection's first contact (``LD a`` / ``AND b`` ->
                ``LD b``); negating one operand is negate's mutant (each operand is one line)
timer           TON <-> TOF <-> IMP (RTO takes three inputs, so it is no slip for these)
time-base       a timer's time-base code one step off: ``ton casovac.0`` -> ``casovac.1`` (10 ms -> 100 ms)
boundary        a comparison at its boundary: ``GT n`` -> ``GT n-1`` (> for >=) and ``LT n`` -> ``LT n+1``
                (< for <=), the set having no GE or LE; the flags S0.1 (<) <-> S0.2 (<=)
constant        a ``#def NAME 25`` value, or an immediate operand of LD, EQ, LT, GT, moved by one step
drop            one instruction dropped (its line keeps its label and comment)
swap            two adjacent instructions of a process exchanged (comment lines between them stay)
=============== ================================================================================

A constant step is the preset step of :mod:`plcsim.mutate.mutant` (one unit in the decimal place below the
leading digit, at least 1: ``#def zpozdeni 25`` -> 24 / 26, ``LD 1`` -> 0 / 2), written in the
literal's own notation (``$0A`` -> ``$09`` / ``$0B``, ``%0011`` -> ``%0010`` / ``%0100``); other notations and
expressions are left alone. ``P n`` and ``E n`` bracket a process and ``L n`` or ``name:`` mark a
jump target: they are not mutated, and no swap moves an instruction across them.

>>> for mutant in derive_il_mutants("LD  START  ; START\\nANC STOP\\n"):
...     print(mutant)
line 1: LD START → LDC START
line 1: LD START dropped
line 1: LD START dropped: a forgotten contact, ANC STOP → LDC STOP
line 1: LD START ⇄ ANC STOP (lines 1 and 2)
line 2: ANC STOP → AND STOP
line 2: ANC STOP → ORC STOP
line 2: ANC STOP dropped: a forgotten contact
"""

from __future__ import annotations

import re
from collections.abc import Iterator
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from plcsim.controllers.tecomat.mnemonics import DEFINED
from plcsim.controllers.tecomat.numbers import NumberError, number
from plcsim.frontends.il import IlProgram, io_symbols
from plcsim.mutate.mutant import Mutant, preset_steps

if TYPE_CHECKING:
    from plcsim.exercise.model import Exercise

_NEGATED = {"LD": "LDC", "AND": "ANC", "OR": "ORC", "XOR": "XOC", "WR": "WRC"}
NEGATE = {**_NEGATED, **{v: k for k, v in _NEGATED.items()}}
SET_RESET = {"SET": "RES", "RES": "SET"}
AND_OR = {"AND": "OR", "OR": "AND", "ANC": "ORC", "ORC": "ANC"}
SERIES_PARALLEL = ("AND", "ANC", "OR", "ORC", "XOR", "XOC")
"""The instructions that connect one more contact (their operand) to the result: the operands drop-operand drops."""
TIMERS = ("TON", "TOF", "IMP")
COMPARE = ("EQ", "LT", "GT")
_FLAGS = {"S0.1": "S0.2", "S0.2": "S0.1"}
_STRUCTURE = frozenset({"P", "E", "L"})
_LINE = re.compile(
    r"^(?P<lead>\s*(?:[^\W\d]\w*\s*:\s*)?)(?P<mnemonic>[A-Za-z]+)(?P<gap>\s*)(?P<arg>.*?)(?P<trail>\s*)$"
)
_DEF = re.compile(r"^(?P<head>\s*#def\s+\w+\s+)(?P<value>\S+)(?P<trail>\s*)$", re.IGNORECASE)
_TIME_BASE = re.compile(r"^(?P<word>[^\W\d]\w*)\s*\.\s*(?P<code>[0-3])$")
_LITERAL = re.compile(r"^(\d+|\$[0-9A-Fa-f]+|%[01]+)$")


@dataclass(frozen=True)
class _Line:
    """One source line split where a mutant changes it: the code and its comment."""

    number: int
    code: str
    comment: str

    @classmethod
    def of(cls, number: int, raw: str) -> _Line:
        code, sep, comment = raw.partition(";")
        return cls(number, code, sep + comment)


@dataclass(frozen=True)
class _Instruction:
    """An instruction line: label prefix, mnemonic, operand and the spacing between them."""

    line: _Line
    lead: str
    mnemonic: str
    gap: str
    arg: str
    trail: str

    @property
    def key(self) -> str:
        return self.mnemonic.upper()

    @property
    def text(self) -> str:
        return f"{self.mnemonic} {self.arg}".rstrip()

    def cased(self, mnemonic: str) -> str:
        """``mnemonic`` in the case this one is written in (``ld`` -> ``ldc``)."""
        return mnemonic.lower() if self.mnemonic.islower() else mnemonic

    def with_mnemonic(self, new: str) -> str:
        return self.rebuilt(new + self.gap + self.arg)

    def with_arg(self, new: str) -> str:
        return self.rebuilt(self.mnemonic + (self.gap or " ") + new)

    def rebuilt(self, body: str) -> str:
        return self.lead + body + self.trail + self.line.comment


def derive_il_mutants(text: str) -> list[Mutant]:
    """Every mutant of the ``.il`` program ``text`` (see the module docstring), in line order.

    Mutants whose text equals the original or an earlier mutant are left out; the order is deterministic.
    """
    raw = text.splitlines()
    ending = "\n" if text.endswith("\n") else ""
    seen = {text}
    found: list[tuple[str, int, str, str]] = []
    for operator, line, description, changes in _sites(raw):
        lines = list(raw)
        for number_, new in changes.items():
            lines[number_ - 1] = new
        mutated = "\n".join(lines) + ending
        if mutated not in seen:
            seen.add(mutated)
            found.append((operator, line, description, mutated))
    found.sort(key=lambda m: m[1])  # stable: by line, then in the order derived
    return [Mutant(k, *m) for k, m in enumerate(found, 1)]


def load_il(text: str, filename: str, tags: Any = None) -> IlProgram:
    """A mutant as a program of the IL front end, assembled against the I/O table ``tags`` at once so
    that one that does not assemble raises :class:`~plcsim.controllers.tecomat.assembly.AssemblyError` (stillborn)."""
    from plcsim.controllers.tecomat.assembler import assemble

    assemble(text, filename, predefined=io_symbols(tags))
    return IlProgram(text, filename)


def reference_mutants(exercise: Exercise) -> list[Mutant]:
    """The mutants of an exercise's instruction-list reference (read as the Tecomat front end reads it)."""
    return derive_il_mutants(IlProgram.from_file(exercise.reference.path).text)


def load_mutant(source: str, filename: str, exercise: Exercise) -> IlProgram:
    """A mutant as a program of the IL front end, assembled against the exercise's I/O table (see :func:`load_il`)."""
    return load_il(source, filename, exercise.tag_table())


Site = tuple[str, int, str, dict[int, str]]
"""Operator, line, description and the changed lines (line number -> new text)."""


def _sites(raw: list[str]) -> Iterator[Site]:
    constants = _constant_names(raw)
    previous: _Instruction | None = None
    for k, text in enumerate(raw, 1):
        line = _Line.of(k, text)
        if line.code.strip().startswith("#"):
            yield from _def_sites(line)
            continue
        ins = _instruction(line)
        if ins is None:
            continue
        if ins.key in _STRUCTURE:
            previous = None
            continue
        if previous is not None and not ins.lead.strip():
            yield from _first_operand_dropped(previous, ins, constants)
        yield from _instruction_sites(ins, constants)
        if previous is not None and not ins.lead.strip():  # a label marks a place: nothing moves across it
            a, b = previous, ins
            yield (
                "swap",
                a.line.number,
                f"{a.text} ⇄ {b.text} (lines {a.line.number} and {b.line.number})",
                {a.line.number: a.rebuilt(_body(b)), b.line.number: b.rebuilt(_body(a))},
            )
        yield "drop", k, f"{ins.text} dropped", {k: (ins.lead + line.comment).rstrip()}
        previous = ins


def _body(ins: _Instruction) -> str:
    return ins.mnemonic + ins.gap + ins.arg


def _instruction(line: _Line) -> _Instruction | None:
    match = _LINE.match(line.code)
    if match is None or match["mnemonic"].upper() not in DEFINED:
        return None
    return _Instruction(line, match["lead"], match["mnemonic"], match["gap"], match["arg"], match["trail"])


def _instruction_sites(ins: _Instruction, constants: set[str]) -> Iterator[Site]:
    k, key, arg = ins.line.number, ins.key, ins.arg.strip()
    is_number = _is_number(arg) or arg.lower() in constants

    def change(operator: str, new: str) -> Site:
        new = ins.cased(new)
        return operator, k, f"{ins.text} → {new} {ins.arg}".rstrip(), {k: ins.with_mnemonic(new)}

    if key in NEGATE and arg and not is_number:
        yield change("negate", NEGATE[key])
    if key in SET_RESET:
        yield change("set-reset", SET_RESET[key])
    if key in AND_OR:
        yield change("and-or", AND_OR[key])
    if key in SERIES_PARALLEL and arg and not is_number:
        yield "drop-operand", k, f"{ins.text} dropped: a forgotten contact", {k: (ins.lead + ins.line.comment).rstrip()}
    if key in TIMERS:
        for other in TIMERS:
            if other != key:
                yield change("timer", other)
    code = _TIME_BASE.match(arg)
    if key in (*TIMERS, "RTO") and code is not None:
        for other in (int(code["code"]) - 1, int(code["code"]) + 1):
            if 0 <= other <= 3:
                new = f"{code['word']}.{other}"
                yield "time-base", k, f"{ins.text} → {ins.mnemonic} {new}", {k: ins.with_arg(new)}
    if arg.upper() in _FLAGS:
        flag = _FLAGS[arg.upper()]
        yield "boundary", k, f"{ins.text} → {ins.mnemonic} {flag}", {k: ins.with_arg(flag)}
    if key in COMPARE or key == "LD":
        literal = _LITERAL.match(arg)
        if literal is None:
            return
        value = number(arg)
        if key in ("GT", "LT"):
            bound = value - 1 if key == "GT" else value + 1
            if bound >= 0:
                new = _written_like(arg, bound)
                yield "boundary", k, f"{ins.text} → {ins.mnemonic} {new}", {k: ins.with_arg(new)}
        for step in preset_steps(value):
            new = _written_like(arg, step)
            yield "constant", k, f"{ins.text} → {ins.mnemonic} {new}", {k: ins.with_arg(new)}


def _first_operand_dropped(first: _Instruction, then: _Instruction, constants: set[str]) -> Iterator[Site]:
    """``LD a`` / ``AND b`` -> ``LD b``: the first contact of a series or parallel connection forgotten, the next one
    loaded in its place (``ANC b`` and ``ORC b`` -> ``LDC b``)."""
    if first.key not in ("LD", "LDC") or then.key not in SERIES_PARALLEL:
        return
    a, b = first.arg.strip(), then.arg.strip()
    if not (a and b) or any(_is_number(x) or x.lower() in constants for x in (a, b)):
        return
    load = then.cased("LDC" if then.key in ("ANC", "ORC", "XOC") else "LD")
    yield (
        "drop-operand",
        first.line.number,
        f"{first.text} dropped: a forgotten contact, {then.text} → {load} {then.arg}".rstrip(),
        {first.line.number: (first.lead + first.line.comment).rstrip(), then.line.number: then.with_mnemonic(load)},
    )


def _def_sites(line: _Line) -> Iterator[Site]:
    match = _DEF.match(line.code)
    if match is None or not _LITERAL.match(match["value"]):
        return
    old = match["value"]
    for step in preset_steps(number(old)):
        new = _written_like(old, step)
        head = " ".join(match["head"].split())
        changed = match["head"] + new + match["trail"] + line.comment
        yield "constant", line.number, f"{head} {old} → {new}", {line.number: changed}


def _constant_names(raw: list[str]) -> set[str]:
    """The lower-case names a ``#def`` makes a constant (``#def zpozdeni 25``), which no contact reads."""
    out = set()
    for text in raw:
        match = _DEF.match(_Line.of(0, text).code)
        if match is not None and _is_number(match["value"]):
            out.add(match["head"].split()[1].lower())
    return out


def _is_number(text: str) -> bool:
    if not text:
        return False
    try:
        number(text)
    except NumberError:
        return False
    return True


def _written_like(literal: str, value: int) -> str:
    """``value`` in the notation of ``literal``: decimal, ``$`` hex (its case, at least its digits) or
    ``%`` binary (at least its digits)."""
    if literal.startswith("$"):
        digits = f"{value:0{len(literal) - 1}X}"
        return "$" + (digits.lower() if literal[1:].islower() else digits)
    if literal.startswith("%"):
        return f"%{value:0{len(literal) - 1}b}"
    return str(value)


__all__ = ["derive_il_mutants", "load_il", "reference_mutants", "load_mutant"]
