"""The ladder (LAD) form of a program: networks of rungs, as the course and TIA Portal draw them.

A rung is a :class:`Series` from the left power rail: contacts, parallel branches (OR), inverted groups
(NOT), function-block boxes the power flows through (TON, CTU, R_TRIG ...), and at its end the outputs:
coils (``=``, ``S``, ``R``), boxes with EN (MOVE, ADD, CALCULATE ...), jumps, or a :class:`Fork` of
output branches. Every element keeps the expression or statement it was read from, so that
:mod:`plcsim.ladder.semantics` can run the drawing as LAD runs (every contact evaluated, left to right,
top to bottom) and the tests can prove it does what the program's own network does.

A statement with no ladder form (a loop, a call of a box behind ``and``) is a :class:`TextBox`: the
program's own lines, drawn as TIA draws an SCL network inside a LAD block.
"""

from __future__ import annotations

import ast
from dataclasses import dataclass, field


@dataclass(frozen=True)
class Contact:
    """A contact: ``NO`` (``--| |--``), ``NC`` (``--|/|--``), ``P`` or ``N`` (edge, with its memory bit)."""

    kind: str
    operand: str
    source: ast.expr
    memory: str = ""


@dataclass(frozen=True)
class Compare:
    """A compare contact (``CMP ==``, ``CMP >=`` ...) between two operands."""

    op: str
    left: str
    right: str
    source: ast.expr


@dataclass(frozen=True)
class FunctionContact:
    """A Bool function drawn in series like a contact (``IN_RANGE`` with MIN, VAL, MAX)."""

    name: str
    pins: tuple[tuple[str, str], ...]
    source: ast.expr


@dataclass(frozen=True)
class Invert:
    """The NOT contact over a group: the inner series, then ``--|NOT|--``."""

    inner: Series


@dataclass(frozen=True)
class Parallel:
    """Branches that open and close on the rung (OR)."""

    branches: tuple[Series, ...]


@dataclass(frozen=True)
class Box:
    """A function-block box the power flows through: the RLO enters at ``rung_pin`` (IN, CU, CLK) and
    the box's Q leaves it. ``pins`` are its other inputs (PT, PV, R ...) as written."""

    instruction: str
    instance: str
    rung_pin: str
    pins: tuple[tuple[str, str, ast.expr], ...]
    outputs: tuple[str, ...]
    call: ast.Call
    instance_source: ast.expr


@dataclass(frozen=True)
class Coil:
    """A coil at the end of a path: ``=`` (assign the RLO), ``S`` (set), ``R`` (reset)."""

    kind: str
    operand: str
    target: ast.expr


@dataclass(frozen=True)
class Operation:
    """A box with EN at the end of a path: MOVE, ADD/SUB/MUL/DIV/MOD, a math function, RD_LOC_T or
    CALCULATE (``OUT := expression``); ``statement`` is the statement it stands for, run when EN carries
    power. ``outputs`` are its output pins and where they go."""

    name: str
    inputs: tuple[tuple[str, str], ...]
    outputs: tuple[tuple[str, str], ...]
    statement: ast.stmt


@dataclass(frozen=True)
class CallCoil:
    """An instruction drawn as a coil: ``--(JMP)--`` / ``--(RET)--``, ``--(RT)--`` (reset a timer),
    ``--(PT)--`` (load a preset); ``statement`` is the call as written, run when the coil has power."""

    kind: str
    operand: str
    statement: ast.stmt


@dataclass(frozen=True)
class Fork:
    """Output branches at the end of a rung, run top to bottom (several coils or boxes on one rung)."""

    branches: tuple[Series, ...]


Element = Contact | Compare | FunctionContact | Invert | Parallel | Box | Coil | Operation | CallCoil | Fork


@dataclass(frozen=True)
class Series:
    """Elements in series, left to right; an output element, if any, is the last."""

    items: tuple[Element, ...] = ()


@dataclass(frozen=True)
class Rung:
    """One rung of a network, from the statement(s) at ``lines`` of the program."""

    series: Series
    lines: tuple[int, int]


@dataclass(frozen=True)
class Alias:
    """``d = t.DATA``: a local name for a structure; drawn in place of the name (``"DATA".X``), not a rung."""

    name: str
    shown: str
    statement: ast.stmt
    lines: tuple[int, int]


@dataclass(frozen=True)
class TextBox:
    """Statements with no ladder form, shown as their own text (TIA's SCL network inside a LAD block)."""

    text: str
    statements: tuple[ast.stmt, ...]
    lines: tuple[int, int]
    reason: str


Part = Rung | TextBox | Alias


@dataclass
class Network:
    """One network: a function of the program, with its number, title, comment and rungs."""

    number: int
    name: str
    title: str
    comment: str
    label: str | None
    parts: list[Part]
    lineno: int
    root: str = "t"
    """The network's parameter that holds the tags (``def name(t)``)."""

    @property
    def rungs(self) -> list[Rung]:
        return [p for p in self.parts if isinstance(p, Rung)]

    @property
    def text_boxes(self) -> list[TextBox]:
        return [p for p in self.parts if isinstance(p, TextBox)]


@dataclass
class Block:
    """One organisation block (OB1, OB30 ...) and its networks in order."""

    name: str
    networks: list[Network] = field(default_factory=list)
