"""What several commands print or pick alike: the verdicts of checks, a shipped solution by name."""

from __future__ import annotations

from typing import Any

from plcsim.core.errors import PlcError


def print_verdicts(results: list[Any], console: Any) -> None:
    """One line per check, ✓ or ✗, with a failed check's message under it (escaped: it may quote a program)."""
    from rich.text import Text

    from plcsim.core.untrusted_text import for_terminal

    for check, verdict in results:
        mark = ("✓", "green") if verdict.passed else ("✗", "red")
        message = for_terminal(verdict.message, newlines=True).replace("\n", "\n      ")
        said = "" if verdict.passed else f"\n      {message}"
        console.print(Text.assemble("  ", mark, f" {for_terminal(check.title)}{said}"), highlight=False)


def shipped_solution(exercise: Any, name: str | None) -> Any:
    """A shipped solution by name, or the reference; a clear error where the exercise ships none."""
    if name:
        return exercise.solution(name)
    if not any(s.kind == "reference" for s in exercise.solutions):
        raise PlcError(f"exercise {exercise.number} ships no reference solution; run yours with --program FILE.py")
    return exercise.reference
