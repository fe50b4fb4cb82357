"""The PLC836 subset's words: its mnemonics, numbers, typed addresses and the time unit of ``doba``.

Shared by the profile (what ``plcsim list --profiles`` shows) and the ``.mech`` front end that reads the
files (:mod:`plcsim.frontends.mech.parse`).
"""

from __future__ import annotations

import re

TIME_UNIT_MS = 20
"""One count of ``doba`` in ms: the chapter's three examples agree on 20 ms (500 = 10 s, 50 = 1 s,
10 = 0.2 s); it never states the unit (spec §7 item 4)."""

STATES = ("EX", "EX0", "EX1", "BEX", "TEX0", "TEX1", "TIM")
"""The EX-type instructions (BEX with them, as §4.2 of the source groups it)."""
ARITY = {
    "LDR": (1, 1),
    "LO": (1, 1),
    "LA": (1, 1),
    "WR": (1, 1),
    "FL": (2, 2),
    "LOD": (1, 1),
    "STO": (1, 1),
    "JUM": (1, 1),
    "EQUI": (2, 2),
    "DS": (1, 1),
    "MECH_BEGIN": (1, 1),
    "MECH_END": (1, 1),
    "MECH_INIT": (1, 1),
    "EX": (0, 0),
    "EX0": (0, 0),
    "EX1": (0, 0),
    "BEX": (0, 0),
    "TEX0": (3, 4),
    "TEX1": (3, 4),
    "TIM": (2, 2),
}
USAGE = {
    "LDR": "LDR NAME (or LDR -NAME)",
    "LO": "LO NAME",
    "LA": "LA NAME",
    "WR": "WR NAME",
    "FL": "FL 1,NAME or FL 0,NAME",
    "LOD": "LOD VALUE",
    "STO": "STO NAME",
    "JUM": "JUM LABEL",
    "EQUI": "EQUI NAME,VALUE",
    "DS": "NAME: DS BYTES",
    "MECH_BEGIN": "MECH_BEGIN NAME",
    "MECH_END": "MECH_END NAME",
    "MECH_INIT": "MECH_INIT NAME",
    "TEX0": "TEX0 COUNTER,TIME,LABEL[,ERROR] (COUNTER may be -)",
    "TEX1": "TEX1 COUNTER,TIME,LABEL[,ERROR] (COUNTER may be -)",
    "TIM": "TIM COUNTER,TIME (COUNTER may be -)",
}
NAME = re.compile(r"^[A-Za-z_?@][A-Za-z0-9_?@]{0,30}$")
"""A name or label: at most 31 letters, digits, ``_ ? @``, not starting with a digit."""
ADDRESS = re.compile(r"^\(\s*([A-Za-z_?@][A-Za-z0-9_?@]*)\s*\+\s*([0-9][0-9A-Fa-f]*[Hh]?)\s*\)$")


def number(text: str) -> int | None:
    """A decimal or ``H``-suffixed hexadecimal number, or None.

    >>> number("12H"), number("23h"), number("50"), number("04"), number("D1")
    (18, 35, 50, 4, None)
    """
    text = text.strip()
    if re.fullmatch(r"[0-9]+", text):
        return int(text, 10)
    if re.fullmatch(r"[0-9][0-9A-Fa-f]*[Hh]", text):
        return int(text[:-1], 16)
    return None


def split_typed(text: str) -> tuple[str | None, str]:
    """``WORD.(CITAC+30)`` -> (``"WORD"``, ``"(CITAC+30)"``); no prefix -> (None, text)."""
    head, dot, rest = text.partition(".")
    if dot and head.upper() in ("BYTE", "WORD"):
        return head.upper(), rest.strip()
    return None, text


def address(text: str) -> tuple[str, int] | None:
    """``(REKONFIG+14)`` -> (``"REKONFIG"``, 14), or None if ``text`` is no such address."""
    match = ADDRESS.match(text.strip())
    if match is None:
        return None
    offset = number(match.group(2))
    return (match.group(1), offset) if offset is not None else None
