"""The decoded program: what the assembler produces and the machine, the instructions and the CPU use.

An :class:`Assembly` is a whole ``.il`` program read once: its :class:`Instruction` list (mnemonic and a
decoded argument: an :class:`~plcsim.controllers.tecomat.memory.Operand`, a :class:`Label`, a
:class:`Timer`, a :class:`Table`, a number), where each process starts, its labels, names and tables.
The types live apart from the parser (:mod:`.assembler`, :mod:`.decoder`) so that the modules running a
program import what it is, not how it is read.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

from plcsim.controllers.tecomat.memory import Operand
from plcsim.core.errors import ProgramError


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
