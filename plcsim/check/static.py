"""Checks of the program text rather than its run (``program_uses_no("SET")``)."""

from __future__ import annotations

from dataclasses import dataclass

from plcsim.check.base import Check, Context, Verdict


@dataclass
class StaticCheck(Check):
    """A statement about the program text rather than its run."""

    instruction: str
    forbidden: bool = True
    name: str | None = None
    weight: float = 1.0

    def describe(self) -> str:
        word = {"SET": "SET coils", "RESET": "RESET coils", "EDGE": "edge instructions"}.get(
            self.instruction, self.instruction
        )
        return f"the program uses no {word}" if self.forbidden else f"the program uses {word}"

    def evaluate(self, ctx: Context) -> Verdict:
        analysis = ctx.analysis
        if analysis is None:
            return Verdict(False, "the program could not be analysed")
        used = analysis.uses(self.instruction)
        if self.instruction == "SET" and used:
            where = ", ".join(f"{target} (line {line})" for target, line in analysis.set_coils[:3])
            detail = f"; SET coils: {where}"
        elif self.instruction == "RESET" and used:
            where = ", ".join(f"{target} (line {line})" for target, line in analysis.reset_coils[:3])
            detail = f"; RESET coils: {where}"
        else:
            detail = ""
        if used == self.forbidden:
            return Verdict(False, f"expected {self.describe()}{detail}")
        return Verdict(True, self.describe())


def program_uses_no(instruction: str) -> StaticCheck:
    """Static check: the program has no ``SET`` (``if c: t.X = True``), ``RESET`` or ``EDGE`` instruction."""
    return StaticCheck(instruction, True)
