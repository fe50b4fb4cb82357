"""Immediate operands in every notation of the Tecomat manual (§4.2), and ``#def`` constant expressions.

Decimal needs no mark; ``%`` is binary and ``$`` hexadecimal; any base is written ``#b#digits`` or
``b#digits`` (copy A and copy B of the manual differ on the leading ``#``, so both are read), spaces may
group the digits; base 60 separates its digits with dots (``# 60# 15.28.35`` is 15 h 28 min 35 s in
seconds). A ``#`` before a plain number (``add #10``) is decimal. Expressions add and subtract
constants and ``#def`` names (``gt modulo-1``).

>>> [number(text) for text in ("45", "%1011", "# 2# 1011", "#16# AF", "$AF", "# 60# 15.28.35", "#10")]
[45, 11, 11, 175, 175, 55715, 10]
>>> hex(number("#2# 1001 1111 0111 0101")), number("% 0000 1111"), number("2# 1111")
('0x9f75', 15, 15)
>>> expression("modulo-1", {"modulo": 10})
9
"""

from __future__ import annotations

import re
from collections.abc import Callable, Mapping

DIGITS = "0123456789ABCDEFGHIJKLMNOPQRSTUVWXYZ"
_BASED = re.compile(r"^#?\s*(\d+)\s*#\s*(.+)$")
_TERM = re.compile(r"\s*([+-])?\s*([^+-]+)")


class NumberError(ValueError):
    """Text that is not a number in any of the manual's notations (the message says which it tried)."""


def number(text: str) -> int:
    """The value of one immediate, in any notation of the manual (NumberError if it is none)."""
    raw = text.strip()
    if not raw:
        raise NumberError("an empty number")
    if raw[0] == "%":
        return _digits(raw[1:], 2, raw)
    if raw[0] == "$":
        return _digits(raw[1:], 16, raw)
    based = _BASED.match(raw)
    if based:
        base = int(based.group(1))
        if not 2 <= base <= 60:
            raise NumberError(f"{raw!r}: the base {base} is not between 2 and 60")
        if base > 36 or "." in based.group(2):
            return _dotted(based.group(2), base, raw)
        return _digits(based.group(2), base, raw)
    if raw[0] == "#":
        raw = raw[1:].strip()
    if raw.isdigit():
        return int(raw)
    raise NumberError(f"{text.strip()!r} is not a number (write 45, %1011, $AF, #2#1011 or #60#15.28.35)")


def _digits(body: str, base: int, raw: str) -> int:
    body = body.replace(" ", "").replace("_", "").upper()
    if not body:
        raise NumberError(f"{raw!r} has no digits")
    value = 0
    for ch in body:
        digit = DIGITS.find(ch)
        if digit < 0 or digit >= base:
            raise NumberError(f"{raw!r}: {ch!r} is not a digit in base {base}")
        value = value * base + digit
    return value


def _dotted(body: str, base: int, raw: str) -> int:
    value = 0
    for part in body.replace(" ", "").split("."):
        if not part.isdigit() or int(part) >= base:
            raise NumberError(f"{raw!r}: {part!r} is not a digit in base {base} (separate the digits with dots)")
        value = value * base + int(part)
    return value


def expression(text: str, constants: Mapping[str, int], resolve: Callable[[str], int] | None = None) -> int:
    """The value of ``a + b - 1`` over numbers and named constants (case-insensitive names)."""
    raw = text.strip()
    try:
        return number(raw)
    except NumberError:
        if raw[:1] in "%$#" or (not re.search(r"[+-]", raw[1:]) and raw[:1].isdigit()):
            raise
    pos, total, terms = 0, 0, 0
    while pos < len(raw):
        match = _TERM.match(raw, pos)
        if match is None or not match.group(2).strip():
            raise NumberError(f"{raw!r} is not a constant expression (numbers and #def names joined by + and -)")
        sign, term = match.group(1), match.group(2).strip()
        if terms and sign is None:
            raise NumberError(f"{raw!r} is not a constant expression")
        key = term.lower()
        if key in constants:
            value = constants[key]
        elif resolve is not None and not term[:1].isdigit() and term[:1] not in "%$#":
            value = resolve(term)
        else:
            value = number(term)
        total += -value if sign == "-" else value
        terms += 1
        pos = match.end()
    return total
