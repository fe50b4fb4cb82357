"""Front ends, chosen by file suffix: each reads a source file into a program the CPU can load.

``.py`` (the Python subset, :class:`plcsim.program.Program`) is the one today; another registers with
:func:`register` (``register(".il", read_il)``), or from another package through the entry-point group
``plcsim.frontends`` (:mod:`plcsim.registry`), and every tool that reads a program file through
:func:`read_program` accepts it.

>>> sorted(suffixes())
['.il', '.py']
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path

from plcsim import registry
from plcsim.errors import ProgramError
from plcsim.loaded import SourceProgram

Reader = Callable[[Path], SourceProgram]
_READERS: dict[str, Reader] = {}


def register(suffix: str, reader: Reader) -> None:
    """Make ``reader`` the front end of files ending in ``suffix`` (``".py"``); a later call replaces it."""
    if not suffix.startswith(".") or len(suffix) < 2:
        raise ValueError(f"a front end's suffix starts with a dot, like '.il', not {suffix!r}")
    _READERS[suffix.lower()] = reader


def unregister(suffix: str) -> None:
    """Forget the front end of ``suffix`` (tests register a throw-away one)."""
    _READERS.pop(suffix.lower(), None)


def suffixes() -> list[str]:
    """The file suffixes a front end is registered for (here, or by another package's entry point)."""
    return list(dict.fromkeys([*_READERS, *registry.frontend_suffixes()]))


def read_program(path: str | Path) -> SourceProgram:
    """Read a program file with the front end its suffix names (errors name the file and the fix)."""
    path = Path(path)
    suffix = path.suffix.lower()
    reader = _READERS.get(suffix) or (registry.frontend(suffix) if suffix else None)
    if reader is None:
        known = ", ".join(sorted(suffixes()))
        raise ProgramError(f"{path}: no front end reads {path.suffix or 'files without a suffix'}; use {known}")
    return reader(path)


def _read_python(path: Path) -> SourceProgram:
    from plcsim.program import Program

    return Program.from_file(path)


register(".py", _read_python)


def _read_il(path: Path) -> SourceProgram:
    from plcsim.frontends.il import read_il

    return read_il(path)  # type: ignore[return-value]


register(".il", _read_il)
