"""Errors plcsim raises: one base class, a few subclasses, each naming the place and the fix."""

from __future__ import annotations

import difflib
import sys
from collections.abc import Iterable, Sequence


class PlcError(Exception):
    """Base class of every error plcsim raises on purpose."""


class LiteralError(PlcError, ValueError):
    """A TIME, number or date literal that cannot be parsed."""


class AddressError(PlcError, ValueError):
    """An absolute address with bad syntax, a bad range or the wrong width."""


class UnknownTagError(PlcError, KeyError):
    """A symbolic name that is not in the tag table or data block."""

    def __str__(self) -> str:  # KeyError would repr() the message
        return str(self.args[0]) if self.args else ""


class PlcTypeError(PlcError, TypeError):
    """A value of the wrong S7 type (a MOVE of REAL into BOOL, a string as a timer preset)."""


class DeclarationError(PlcError, ValueError):
    """A tag, data block or task declared twice, at a used address, or with a bad option."""


class ProgramError(PlcError):
    """A user program that cannot be loaded: syntax, the PLC subset of Python, labels and jumps."""


class SubsetError(ProgramError):
    """A construct outside the PLC subset of Python (imports, dunder access, open/exec/eval)."""


class NoOB1Error(ProgramError):
    """A program with no OB1 (an empty file, only comments, ``def ob1``): it would never run."""


class ProgramFileError(ProgramError):
    """A program file that cannot be read or decoded (the message names the encoding tried)."""


class ConfigurationError(PlcError, ValueError):
    """A CPU, wiring, scenario or exercise option with an invalid value."""


class ExerciseError(ConfigurationError):
    """An instructor's mistake in an exercise: a name its tags, wiring or plant lack, a negative time.

    Raised when the exercise is loaded (or, for what only a run reveals, by the run): never a student's
    failure. ``problems`` holds every mistake found, each starting with the ``file:line`` that made it.
    """

    def __init__(self, message: str, problems: Sequence[str] = ()):
        super().__init__(message)
        self.problems = list(problems) or [message]


def defined_at() -> str:
    """``file:line`` of the innermost caller outside plcsim: where an instructor wrote a scenario or check."""
    frame = sys._getframe(1)
    while frame is not None and str(frame.f_globals.get("__name__", "")).startswith("plcsim."):
        frame = frame.f_back  # type: ignore[assignment]
    return "?" if frame is None else f"{frame.f_code.co_filename}:{frame.f_lineno}"


def did_you_mean(name: str, choices: Iterable[str], n: int = 3) -> str:
    """Return a "did you mean" hint listing the names nearest to ``name`` (empty if none is near).

    >>> did_you_mean("TLACIDO", ["TLACIDLO", "LED"])
    "; did you mean 'TLACIDLO'?"
    """
    choices = list(choices)
    near = difflib.get_close_matches(name, choices, n=n, cutoff=0.6)
    if not near:
        lowered = {c.lower(): c for c in choices}
        near = [lowered[c] for c in difflib.get_close_matches(name.lower(), list(lowered), n=n)]
    if not near:
        return ""
    return "; did you mean " + " or ".join(repr(c) for c in near) + "?"
