"""Mutants of PLC836 mechanism programs (``.mech``): the slips the chapter warns about, one line each.

:mod:`plcsim.mutate.engine` grades them like the mutants of a Python or ``.il`` program; this module only
derives them. A mutant is the reference's text with one line changed (a swap changes two), comments kept:

========== ==================================================================================
negate     a contact negated: ``LDR x`` <-> ``LDR -x`` (also LO, LA)
and-or     a series connection for a parallel one: LA <-> LO
set-reset  ``FL 1,x`` <-> ``FL 0,x``
polarity   the digit of a state: EX0 <-> EX1, TEX0 <-> TEX1 (the digit names the value that blocks)
no-limit   a timed state without its limit: ``TEX0 c,t,lbl`` -> ``EX0`` (the chapter's first CWCCW)
ex-bex     EX <-> BEX (a state that costs a scan, or one that does not)
constant   an ``EQUI`` value, a state's time or error number moved by one preset step
drop       one instruction dropped (its line keeps its label and comment), EX-type states included
swap       two adjacent instructions exchanged (not across a label, MECH_BEGIN or MECH_END)
========== ==================================================================================

>>> for mutant in derive_mech_mutants("MECH_BEGIN M\\nLDR A ;a\\nEX0\\nMECH_END M\\n"):
...     print(mutant)
line 2: LDR A → LDR -A
line 2: LDR A dropped
line 2: LDR A ⇄ EX0 (lines 2 and 3)
line 3: EX0 → EX1
line 3: EX0 dropped
"""

from __future__ import annotations

import re
from collections.abc import Iterator
from typing import TYPE_CHECKING

from plcsim.controllers.plc836.grammar import ARITY, number
from plcsim.frontends.mech.program import MechProgram
from plcsim.mutate.mutant import Mutant, preset_steps

if TYPE_CHECKING:
    from plcsim.exercise.model import Exercise

POLARITY = {"EX0": "EX1", "EX1": "EX0", "TEX0": "TEX1", "TEX1": "TEX0"}
AND_OR = {"LA": "LO", "LO": "LA"}
EX_BEX = {"EX": "BEX", "BEX": "EX"}
_FIXED = frozenset({"MECH_BEGIN", "MECH_END", "EQUI", "DS"})
"""Lines that are structure or declarations: never dropped or swapped."""
_LINE = re.compile(
    r"^(?P<lead>\s*(?:[A-Za-z_?@][A-Za-z0-9_?@]*\s*:\s*)?)(?P<op>[A-Za-z_][A-Za-z0-9_]*)(?P<gap>\s*)(?P<arg>[^;]*?)"
    r"(?P<trail>\s*)(?P<comment>;.*)?$"
)

Site = tuple[str, int, str, dict[int, str]]
"""Operator, line, description and the changed lines (line number -> new text)."""


class _Ins:
    """An instruction line split where a mutant changes it."""

    def __init__(self, number: int, match: re.Match[str]):
        self.number = number
        self.lead, self.op, self.gap = match["lead"], match["op"], match["gap"]
        self.arg, self.trail, self.comment = match["arg"], match["trail"], match["comment"] or ""

    @property
    def key(self) -> str:
        return self.op.upper()

    @property
    def args(self) -> list[str]:
        return [a.strip() for a in self.arg.split(",")] if self.arg.strip() else []

    @property
    def text(self) -> str:
        return f"{self.op} {self.arg}".rstrip()

    def body(self) -> str:
        return self.op + self.gap + self.arg

    def rebuilt(self, body: str) -> str:
        return (self.lead + body + self.trail + self.comment).rstrip()

    def with_op(self, op: str) -> str:
        return self.rebuilt(op + self.gap + self.arg)

    def with_args(self, args: list[str]) -> str:
        return self.rebuilt(self.op + (self.gap or " ") + ",".join(args))


def derive_mech_mutants(text: str) -> list[Mutant]:
    """Every mutant of the ``.mech`` program ``text`` (see the module docstring), in line order; mutants
    whose text equals the original or an earlier one are left out."""
    raw = text.splitlines()
    ending = "\n" if text.endswith("\n") else ""
    seen = {text}
    found: list[tuple[str, int, str, str]] = []
    for operator, line, description, changes in _sites(raw):
        lines = list(raw)
        for k, new in changes.items():
            lines[k - 1] = new
        mutated = "\n".join(lines) + ending
        if mutated not in seen:
            seen.add(mutated)
            found.append((operator, line, description, mutated))
    found.sort(key=lambda m: m[1])
    return [Mutant(k, *m) for k, m in enumerate(found, 1)]


def _instruction(k: int, text: str) -> _Ins | None:
    match = _LINE.match(text)
    if match is None or match["op"].upper() not in ARITY:
        return None
    return _Ins(k, match)


def _sites(raw: list[str]) -> Iterator[Site]:
    previous: _Ins | None = None
    for k, text in enumerate(raw, 1):
        ins = _instruction(k, text)
        if ins is None:
            continue
        yield from _instruction_sites(ins)
        if ins.key in _FIXED:
            previous = None
            continue
        if previous is not None and not ins.lead.strip():
            a, b = previous, ins
            yield (
                "swap",
                a.number,
                f"{a.text} ⇄ {b.text} (lines {a.number} and {b.number})",
                {a.number: a.rebuilt(b.body()), b.number: b.rebuilt(a.body())},
            )
        yield "drop", k, f"{ins.text} dropped", {k: (ins.lead + ins.comment).rstrip()}
        previous = ins


def _instruction_sites(ins: _Ins) -> Iterator[Site]:
    k, key, args = ins.number, ins.key, ins.args

    def op(operator: str, new: str) -> Site:
        return operator, k, f"{ins.text} → {new} {ins.arg}".rstrip(), {k: ins.with_op(new)}

    def arg(operator: str, new_args: list[str]) -> Site:
        shown = f"{ins.op} {','.join(new_args)}"
        return operator, k, f"{ins.text} → {shown}", {k: ins.with_args(new_args)}

    if key in ("LDR", "LO", "LA") and args:
        name = args[0]
        yield arg("negate", [name[1:] if name.startswith("-") else f"-{name}"])
    if key in AND_OR:
        yield op("and-or", AND_OR[key])
    if key == "FL" and len(args) == 2 and args[0] in ("0", "1"):
        yield arg("set-reset", ["1" if args[0] == "0" else "0", args[1]])
    if key in POLARITY:
        yield op("polarity", POLARITY[key])
    if key in ("TEX0", "TEX1"):
        yield "no-limit", k, f"{ins.text} → {key[1:]}", {k: ins.rebuilt(ins.op[1:])}
    if key in EX_BEX:
        yield op("ex-bex", EX_BEX[key])
    positions = {"EQUI": (1,), "TEX0": (1, 3), "TEX1": (1, 3), "TIM": (1,)}.get(key, ())
    for i in positions:
        if i < len(args) and number(args[i]) is not None:
            for step in preset_steps(number(args[i])):
                changed = list(args)
                changed[i] = _written_like(args[i], step)
                yield arg("constant", changed)


def _written_like(literal: str, value: int) -> str:
    """``value`` in the notation of ``literal``: decimal (its leading zeros) or ``H``-suffixed hex."""
    if literal[-1] in "Hh":
        return f"{value:0{len(literal) - 1}X}{literal[-1]}"
    return f"{value:0{len(literal)}d}" if literal.startswith("0") else str(value)


def reference_mutants(exercise: Exercise) -> list[Mutant]:
    """The mutants of an exercise's ``.mech`` reference."""
    return derive_mech_mutants(MechProgram.from_file(exercise.reference.path).text)


def load_mutant(source: str, filename: str, exercise: Exercise) -> MechProgram:
    """A mutant as a program of the ``.mech`` front end (ProgramError if it does not read: stillborn)."""
    return MechProgram(source, filename)


__all__ = ["derive_mech_mutants", "load_mutant", "reference_mutants"]
