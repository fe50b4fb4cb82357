"""The Tecomat instruction-list front end: ``.il`` files run on the Tecomat NS950 controller.

The file is read when the front end is chosen and assembled when it meets its controller's I/O table:
the exercise's tag names become symbols (``TLACIDLO`` on %I0.0 is X0.0, ``LED`` on %Q0.0 is Y0.0), so a
program may use them without ``#def`` (its own ``#def`` of a name wins). The S7 CPU refuses such a
program with a message saying where it runs.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import fields
from pathlib import Path
from typing import Any

from plcsim.controllers.tecomat.memory import Operand
from plcsim.core.errors import ProgramError, ProgramFileError
from plcsim.tags.table import Tag, TagTable

S7_ONLY = frozenset({"seed", "clock_memory_byte", "system_memory_byte"})
"""S7 options a Tecomat run ignores without a word: there is no scan jitter to seed, and the Tecomat has
its clock bits (S13) and first-cycle flags (S2) in S instead of clock and system memory bytes."""


class IlProgram:
    """An ``.il`` program: its text and file name, assembled against an I/O table by :meth:`controller`."""

    def __init__(self, text: str, filename: str = "<il>"):
        self.text, self.filename = text, filename

    @classmethod
    def from_file(cls, path: str | Path) -> IlProgram:
        path = Path(path)
        try:
            data = path.read_bytes()
        except OSError as exc:
            raise ProgramFileError(f"{path}: cannot read the program: {exc.strerror}") from None
        return cls(decode_il(data, str(path)), str(path))

    def controller(self, tags: TagTable | Mapping[str, Any] | None = None, **options: Any) -> Any:
        """A Tecomat CPU running this program, its symbols bound to the I/O table ``tags``."""
        from plcsim.controllers.tecomat.assembler import assemble
        from plcsim.controllers.tecomat.cpu import TecomatCPU
        from plcsim.controllers.tecomat.settings import TecomatConfig

        known = {f.name for f in fields(TecomatConfig)}
        chosen = {k: v for k, v in options.items() if k in known}
        ignored = sorted(k for k in options if k not in known and k not in S7_ONLY)
        config = TecomatConfig(**chosen)
        asm = assemble(self.text, self.filename, r_size=config.r_size, predefined=io_symbols(tags))
        cpu = TecomatCPU(asm, config)
        if ignored:
            cpu.warnings.append(f"the Tecomat controller has no option {', '.join(ignored)}; ignored")
        return cpu

    def analysis(self, tags: TagTable | Mapping[str, Any] | None = None) -> Any:
        """What the program uses, assembled against ``tags`` without running it (None if it does not
        assemble: the run reports why)."""
        from plcsim.controllers.tecomat.analysis import IlAnalysis
        from plcsim.controllers.tecomat.assembler import assemble
        from plcsim.controllers.tecomat.assembly import AssemblyError

        try:
            return IlAnalysis.of(assemble(self.text, self.filename, predefined=io_symbols(tags)))
        except AssemblyError:
            return None

    # -- the S7 CPU's front-end protocol: refused, with the way out ---------------------------------

    def declare_into(self, table: TagTable) -> TagTable:
        raise ProgramError(
            f"{self.filename} is a Tecomat instruction-list program: it runs on the Tecomat controller "
            f"(plcsim.controllers.choice.controller_for picks it), not on the S7-1200 CPU"
        )

    def absolute_addresses(self) -> list[str]:
        return []

    def link(self, target: Any) -> Any:
        return self.declare_into(target.table)


def decode_il(data: bytes, filename: str) -> str:
    """An ``.il`` file's text: UTF-8, or else cp1250 (the manual's Czech Windows code page); a file that is
    neither is a ProgramFileError naming the file and the first byte cp1250 does not have.

    >>> try:
    ...     decode_il(b"LD X0.0 ; \\x81", "lab.il")
    ... except ProgramFileError as exc:
    ...     print(str(exc).replace("; ", ";\\n"))
    lab.il, line 1: this file is not text in UTF-8 or cp1250 (byte 0x81 in column 11);
    save it as UTF-8
    """
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError:
        pass
    try:
        return data.decode("cp1250")
    except UnicodeDecodeError as exc:
        line = data.count(b"\n", 0, exc.start) + 1
        column = exc.start - (data.rfind(b"\n", 0, exc.start) + 1) + 1
        raise ProgramFileError(
            f"{filename}, line {line}: this file is not text in UTF-8 or cp1250 (byte 0x{data[exc.start]:02x} in "
            f"column {column}); save it as UTF-8"
        ) from None


AREAS = {"I": "X", "Q": "Y", "M": "R"}


def program_text(text: str, filename: str = "<il>") -> IlProgram:
    """A Tecomat ``.il`` program from text (as :func:`plcsim.frontends.read_program` reads a file)."""
    return IlProgram(text, filename)


def io_symbols(tags: TagTable | Mapping[str, Any] | None) -> dict[str, Operand]:
    """The I/O table's bit, byte, word and double-word tags as operands: inputs in X, outputs in Y, markers
    in R (%I0.1 -> X0.1, %QW2 -> YW2, %MD8 -> RL8); data blocks have no place in the Tecomat's scratchpad."""
    if tags is None:
        return {}
    if not isinstance(tags, TagTable):
        table = TagTable()
        for name, decl in tags.items():
            if isinstance(decl, Tag):
                table.add(name, decl)
        tags = table
    out = {}
    for entry in tags:
        addr = entry.address
        if addr is None or addr.area not in AREAS or addr.bits not in (1, 8, 16, 32):
            continue
        width = {1: "bit", 8: "byte", 16: "word", 32: "long"}[addr.bits]
        out[entry.name] = Operand(AREAS[addr.area], width, addr.byte, addr.bit if addr.bits == 1 else 0)
    return out


def read_il(path: Path) -> IlProgram:
    """The front end's reader for :func:`plcsim.frontends.register`."""
    return IlProgram.from_file(path)
