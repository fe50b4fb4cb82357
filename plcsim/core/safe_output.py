"""Output that never crashes on a console that cannot encode it (Windows' cp1252, a C locale).

Reports print ✓, ✗, – and ×; a stream whose encoding lacks them (a redirected ``plcsim grade`` on
Windows writes cp1252) would raise UnicodeEncodeError and exit with code 1, the code of a failed
student. :func:`make_streams_safe` keeps the stream's encoding and writes an ASCII stand-in for each
character it cannot encode (``+`` for ✓, ``x`` for ✗, ``?`` for the rest).

>>> "✓ 3 / 3 — ok ✗".encode("cp1252", errors=ERRORS)
b'+ 3 / 3 \\x97 ok x'
>>> "✓ 3 / 3 — ok ✗ →".encode("ascii", errors=ERRORS)
b'+ 3 / 3 - ok x ->'
"""

from __future__ import annotations

import codecs
import sys

ERRORS = "plcsim-ascii"
"""The name of the error handler registered with :mod:`codecs`."""

_STAND_INS = {"✓": "+", "✗": "x", "–": "-", "—": "-", "×": "x", "…": "...", "→": "->", "≥": ">=", "≤": "<="}


def _stand_in(error: UnicodeError) -> tuple[str, int]:
    if not isinstance(error, UnicodeEncodeError):
        raise error
    bad = error.object[error.start : error.end]
    return "".join(_STAND_INS.get(ch, "?") for ch in bad), error.end


codecs.register_error(ERRORS, _stand_in)


def make_streams_safe() -> None:
    """Let stdout and stderr write a stand-in for what their encoding cannot encode, instead of raising."""
    for stream in (sys.stdout, sys.stderr):
        reconfigure = getattr(stream, "reconfigure", None)  # a replaced stream (pytest's capture) may lack it
        if reconfigure is not None and getattr(stream, "errors", "strict") == "strict":
            reconfigure(errors=ERRORS)
