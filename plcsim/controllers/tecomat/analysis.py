"""What a Tecomat program uses, for an exercise's static checks (``program_uses_no("SET")``).

The checks speak of the S7 textbook's instructions; an instruction list says them so: SET coils are
``SET``, RESET coils ``RES``, edge instructions ``LET``; any other name is a mnemonic (``"TON"``).

>>> from plcsim.controllers.tecomat.assembler import assemble
>>> a = IlAnalysis.of(assemble("#def LED y0.0\\nLD X0.0\\nSET LED\\n"))
>>> a.uses("SET"), a.uses("RESET"), a.set_coils
(True, False, [('LED', 3)])
"""

from __future__ import annotations

from dataclasses import dataclass, field

from plcsim.controllers.tecomat.assembly import Assembly

CHECK_NAMES = {"SET": "SET", "RESET": "RES", "EDGE": "LET"}


@dataclass
class IlAnalysis:
    """The mnemonics a program uses (with their lines) and where it sets and resets."""

    lines: dict[str, list[int]] = field(default_factory=dict)
    set_coils: list[tuple[str, int]] = field(default_factory=list)
    reset_coils: list[tuple[str, int]] = field(default_factory=list)

    @classmethod
    def of(cls, asm: Assembly) -> IlAnalysis:
        names = {str(s.operand): s.name for s in asm.symbols.values() if s.operand is not None}
        out = cls()
        for instr in asm.code:
            if instr.mnemonic == "E" or (instr.mnemonic == "L" and instr.line == 0):
                continue
            out.lines.setdefault(instr.mnemonic, []).append(instr.line)
            if instr.mnemonic in ("SET", "RES"):
                target = names.get(str(instr.arg), str(instr.arg))
                (out.set_coils if instr.mnemonic == "SET" else out.reset_coils).append((target, instr.line))
        return out

    def uses(self, instruction: str) -> bool:
        """Whether the program has the instruction (a check's name, or a mnemonic)."""
        key = instruction.upper()
        return CHECK_NAMES.get(key, key) in self.lines


@dataclass
class IlCompiled:
    """What the grader reads of a compiled program: its analysis."""

    analysis: IlAnalysis
