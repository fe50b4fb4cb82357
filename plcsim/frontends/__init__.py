"""Front ends, chosen by file suffix: each reads a source file into a program a controller can load.

A front end is described by a :class:`FrontEnd`: the suffix it reads, its reader, the CPU profile its
programs are written for (:mod:`plcsim.controllers.profiles`) and its **contract program**, the self-holding motor of
:data:`CONTRACT_TASK` in its language. ``.py`` (the Python subset, :class:`plcsim.frontends.python.program.Program`, on
the S7-1200) and ``.il`` (the Tecomat instruction list, on the Tecomat NS950) are plcsim's own; another
registers with :func:`register` (``register(".st", read_st, profile="s7-1200", contract=MOTOR_ST)``), or
from another package through the entry-point group ``plcsim.frontends`` (:mod:`plcsim.core.registry`), and
every tool that reads a program file through :func:`read_program` accepts it. The contract test
(``tests/controllers/test_seam_contract.py``) runs every registered front end's contract program and asks for the
Python one's trace digest, bit for bit.

>>> sorted(suffixes()), frontend_for(".il").profile
(['.il', '.py'], 'tecomat-ns950')
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

from plcsim.controllers.loaded import SourceProgram
from plcsim.core import registry
from plcsim.core.errors import ProgramError, ProgramFileError

Reader = Callable[[Path], SourceProgram]
DEFAULT_PROFILE = "s7-1200"

CONTRACT_TAGS = {"START": "%I0.0", "STOP": "%I0.1", "MOTOR": "%Q0.0"}
"""The contract program's I/O table: two push buttons (normally open) and a motor contactor."""
CONTRACT_TASK = (
    "MOTOR := (START OR MOTOR) AND NOT STOP, in one cyclic task: START switches the motor on and it holds "
    "itself; STOP switches it off and dominates."
)


@dataclass(frozen=True)
class FrontEnd:
    """One front end: the file suffix it reads, its reader, its programs' profile and contract program."""

    suffix: str
    read: Reader
    profile: str = DEFAULT_PROFILE
    """The name of the registered CPU profile its programs are written for."""
    language: str = ""
    contract: str | None = None
    """:data:`CONTRACT_TASK` in this front end's language (the text of a file it reads)."""


_FRONT_ENDS: dict[str, FrontEnd] = {}


def register(
    suffix: str,
    reader: Reader,
    *,
    profile: str = DEFAULT_PROFILE,
    language: str = "",
    contract: str | None = None,
) -> None:
    """Make ``reader`` the front end of files ending in ``suffix`` (``".py"``); a later call replaces it."""
    if not suffix.startswith(".") or len(suffix) < 2:
        raise ValueError(f"a front end's suffix starts with a dot, like '.il', not {suffix!r}")
    _FRONT_ENDS[suffix.lower()] = FrontEnd(suffix.lower(), reader, profile, language, contract)


def unregister(suffix: str) -> None:
    """Forget the front end of ``suffix`` (tests register a throw-away one)."""
    _FRONT_ENDS.pop(suffix.lower(), None)


def suffixes() -> list[str]:
    """The file suffixes a front end is registered for (here, or by another package's entry point)."""
    return list(dict.fromkeys([*_FRONT_ENDS, *registry.frontend_suffixes()]))


def frontend_for(suffix: str) -> FrontEnd | None:
    """The front end of files ending in ``suffix``: registered here, or another package's entry point
    (a :class:`FrontEnd`, or a bare reader, whose programs are then taken to be for the S7-1200)."""
    suffix = suffix.lower()
    found = _FRONT_ENDS.get(suffix)
    if found is not None or not suffix:
        return found
    plugged = registry.frontend(suffix)
    if plugged is None or isinstance(plugged, FrontEnd):
        return plugged
    return FrontEnd(suffix, plugged)


def front_ends() -> list[FrontEnd]:
    """Every registered front end, in suffix order."""
    return [f for f in (frontend_for(s) for s in sorted(suffixes())) if f is not None]


def read_program(path: str | Path) -> SourceProgram:
    """Read a program file with the front end its suffix names (errors name the file and the fix)."""
    path = Path(path)
    front = frontend_for(path.suffix)
    if front is None:
        known = ", ".join(sorted(suffixes()))
        raise ProgramError(f"{path}: no front end reads {path.suffix or 'files without a suffix'}; use {known}")
    try:
        return front.read(path)
    except UnicodeDecodeError as exc:  # another package's reader: still the file's fault, named as such
        why = f"{path}: this file is not text in {exc.encoding} (byte {exc.start}: {exc.reason})"
        raise ProgramFileError(f"{why}; save it as {exc.encoding}") from None


def _read_python(path: Path) -> SourceProgram:
    from plcsim.frontends.python.program import Program

    return Program.from_file(path)


register(
    ".py",
    _read_python,
    language="the Python subset",
    contract="def OB1(t):\n    t.MOTOR = (t.START or t.MOTOR) and not t.STOP\n",
)


def _read_il(path: Path) -> SourceProgram:
    from plcsim.frontends.il import read_il

    return read_il(path)  # type: ignore[return-value]


register(
    ".il",
    _read_il,
    profile="tecomat-ns950",
    language="Tecomat NS950 instruction list",
    contract="LD START\nOR MOTOR\nANC STOP\nWR MOTOR\n",
)

__all__ = [
    "CONTRACT_TAGS",
    "CONTRACT_TASK",
    "FrontEnd",
    "front_ends",
    "frontend_for",
    "read_program",
    "register",
    "suffixes",
    "unregister",
]
