"""Reading a ``.mech`` file: the PLC836 subset of seed 003, chapter 4, one instruction a line.

``label:`` may start a line (alone, it names the next instruction), ``;`` starts a comment, numbers are
decimal or hexadecimal with a trailing ``H`` (``12H``). The instructions: ``LDR/LO/LA x`` (``-x`` is
NOT x), ``WR x``, ``FL 1,x`` / ``FL 0,x``, ``LOD v``, ``STO m``, ``JUM label``, ``EQUI name,value``,
``name: DS n``, ``MECH_BEGIN m`` / ``MECH_END m`` / ``MECH_INIT m``, and the states ``EX``, ``EX0``,
``EX1``, ``BEX``, ``TEX0|TEX1 citac,doba,label[,chyba]`` and ``TIM citac,doba`` (``citac`` may be
``-`` or ``NIL``; ``BYTE.``/``WORD.`` before ``citac`` types both operands, then ``doba`` must be an
address such as ``(REKONFIG+14)``). Every error names the file, the line and the fix.

>>> program = parse("EQUI D1,50\\nMECH_BEGIN M\\nLDR A\\nTEX0 -,D1,ERR,4\\nERR:\\nMECH_END M\\n", "m.mech")
>>> [(i.line, i.op, i.args) for i in program.body][1:3]
[(3, 'LDR', ('A',)), (4, 'TEX0', ('-', 'D1', 'ERR', '4'))]
>>> program.mechanisms["M"].states
[4]
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field

from plcsim.controllers.plc836.grammar import (
    ARITY,
    NAME,
    STATES,
    USAGE,
    address,
    number,
    split_typed,
)
from plcsim.core.errors import ProgramError


@dataclass(frozen=True)
class Instruction:
    """One instruction: its line, mnemonic, operands as written and the label before it (if any)."""

    line: int
    op: str
    args: tuple[str, ...]
    label: str | None = None


@dataclass
class MechanismBlock:
    """One ``MECH_BEGIN .. MECH_END``: where it starts and ends in the body and its states' lines."""

    name: str
    begin: int
    end: int = -1
    states: list[int] = field(default_factory=list)


@dataclass
class MechSource:
    """A parsed ``.mech`` file."""

    filename: str
    body: list[Instruction]
    labels: dict[str, int]
    """Label -> index in :attr:`body` of the instruction it names."""
    constants: dict[str, int]
    areas: dict[str, int]
    """``DS`` areas: name -> size in bytes."""
    mechanisms: dict[str, MechanismBlock]


def _fail(filename: str, line: int, message: str) -> ProgramError:
    return ProgramError(f"{filename}, line {line}: {message}")


def _split_line(raw: str) -> tuple[str | None, str, list[str]]:
    code = raw.split(";", 1)[0].strip()
    label = None
    match = re.match(r"^([A-Za-z_?@][A-Za-z0-9_?@]*)\s*:(.*)$", code)
    if match:
        label, code = match.group(1), match.group(2).strip()
    if not code:
        return label, "", []
    op, _, rest = code.partition(" ")
    if "\t" in op:
        op, _, more = op.partition("\t")
        rest = f"{more} {rest}"
    args = [a.strip() for a in rest.split(",")] if rest.strip() else []
    return label, op.upper(), args


def parse(text: str, filename: str = "<mech>") -> MechSource:
    """Read ``text``; a mistake is a ProgramError naming the file, the line and the fix."""
    body: list[Instruction] = []
    labels: dict[str, int] = {}
    constants: dict[str, int] = {}
    areas: dict[str, int] = {}
    mechanisms: dict[str, MechanismBlock] = {}
    pending: list[tuple[str, int]] = []
    current: MechanismBlock | None = None
    for lineno, raw in enumerate(text.splitlines(), 1):
        label, op, args = _split_line(raw)
        if label is not None:
            if label in labels or any(label == p for p, _ in pending):
                raise _fail(filename, lineno, f"label {label} is defined twice; give one of them another name")
            pending.append((label, lineno))
        if not op:
            continue
        if op not in ARITY:
            raise _fail(
                filename,
                lineno,
                f"{op} is not an instruction of the PLC836 subset; use {', '.join(ARITY)}",
            )
        low, high = ARITY[op]
        if not low <= len(args) <= high or any(a == "" for a in args):
            usage = USAGE.get(op, op)
            raise _fail(filename, lineno, f"{raw.split(';', 1)[0].strip()!r}: write {usage}")
        for arg in args:
            if " " in arg and not arg.startswith("(") and "." not in arg:
                raise _fail(
                    filename, lineno, f"operand {arg!r} has a space in it; a name is one word: {arg.replace(' ', '')}"
                )
        if op == "EQUI":
            value = number(args[1]) if args[1] not in constants else constants[args[1]]
            if not NAME.match(args[0]) or value is None:
                raise _fail(
                    filename, lineno, f"write EQUI NAME,VALUE with a number such as 50 or 12H, not {raw.strip()!r}"
                )
            constants[args[0]] = value
            continue
        if op == "DS":
            size = number(args[0])
            name = next((p for p, line in pending if line == lineno), None)
            if name is None or size is None or size <= 0:
                raise _fail(filename, lineno, "write NAME: DS BYTES (a label, then the number of bytes to reserve)")
            pending = [(p, line) for p, line in pending if p != name]
            areas[name] = size
            continue
        if op == "MECH_BEGIN":
            if current is not None:
                raise _fail(
                    filename,
                    lineno,
                    f"MECH_BEGIN {args[0]} inside mechanism {current.name}; close it with MECH_END {current.name} "
                    f"first (mechanisms do not nest)",
                )
            if not NAME.match(args[0]):
                raise _fail(filename, lineno, f"{args[0]!r} is not a mechanism name (letters, digits, _; at most 31)")
            if args[0] in mechanisms:
                raise _fail(filename, lineno, f"mechanism {args[0]} is written twice; give one of them another name")
            current = mechanisms[args[0]] = MechanismBlock(args[0], len(body))
        elif op == "MECH_END":
            if current is None:
                raise _fail(filename, lineno, f"MECH_END {args[0]} without MECH_BEGIN {args[0]} before it")
            if args[0] != current.name:
                raise _fail(
                    filename,
                    lineno,
                    f"MECH_END {args[0]} closes mechanism {current.name}; write MECH_END {current.name}",
                )
            current.end = len(body)
        elif op in STATES:
            if current is None:
                raise _fail(
                    filename,
                    lineno,
                    f"{op} outside a mechanism; EX-type instructions belong between MECH_BEGIN and MECH_END "
                    f"(write the chapter's preparatory-functions module as a mechanism of its own)",
                )
            current.states.append(lineno)
            _check_timing(filename, lineno, op, args)
        for name, _ in pending:
            labels[name] = len(body)
        body.append(Instruction(lineno, op, tuple(args), pending[-1][0] if pending else None))
        pending = []
        if op == "MECH_END":
            current = None
    if current is not None:
        first = body[current.begin].line
        raise _fail(filename, first, f"mechanism {current.name} has no end; write MECH_END {current.name} after it")
    if pending:
        name, line = pending[0]
        raise _fail(filename, line, f"label {name} names no instruction; put one after it")
    return MechSource(filename, body, labels, constants, areas, mechanisms)


def _check_timing(filename: str, lineno: int, op: str, args: list[str]) -> None:
    if op not in ("TEX0", "TEX1", "TIM"):
        return
    kind, counter = split_typed(args[0])
    if kind is not None and counter in ("-", "NIL"):
        raise _fail(filename, lineno, f"{kind}. types a counter; with no counter (-) leave the prefix out")
    if kind is not None and address(args[1]) is None:
        raise _fail(
            filename,
            lineno,
            f"{kind}.{counter} types both operands, so the time {args[1]!r} must be an address such as "
            f"(REKONFIG+14), not a constant; drop the {kind}. prefix to use a constant",
        )
    if kind is not None and address(counter) is None and not NAME.match(counter):
        raise _fail(filename, lineno, f"counter {counter!r}: write a name, (ARRAY+n) or -")
