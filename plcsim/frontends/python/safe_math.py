"""Bounded versions of what could grow without limit: ``**``, ``*``, ``<<``, text ``%`` and ``range``.

No S7 type is wider than 64 bits, so a program never needs an integer of thousands of digits or a
text of a million characters; computing one (``9**9**9``, ``"x" * 10**9``) would only stall the
CPU. The rewrite (:mod:`plcsim.frontends.python.rewrite`) turns these operators into the functions
below; a result beyond the bounds is a :class:`ProgramError` that stops the CPU with the network
named, and a constant expression beyond them is refused when the program is loaded.

>>> _pow(2, 10), _mul("ab", 2), _lshift(1, 4)
(1024, 'abab', 16)
>>> _pow(9, 9**9)
Traceback (most recent call last):
...
plcsim.core.errors.ProgramError: 9 ** 387420489 is far beyond any PLC number (at most 4096 bits)
"""

from __future__ import annotations

import ast
from typing import Any

from plcsim.core.errors import ProgramError

MAX_INT_BITS = 4096
"""The widest integer a result may have (an LInt has 64 bits; the margin is for intermediate values)."""
MAX_SEQUENCE = 100_000
"""The longest text or list a ``*`` may build (an S7 STRING holds 254 characters)."""


def _too_big(left: Any, op: str, right: Any) -> ProgramError:
    return ProgramError(f"{left!r} {op} {right!r} is far beyond any PLC number (at most {MAX_INT_BITS} bits)")


def _pow(base: Any, exponent: Any) -> Any:
    big = isinstance(base, int) and isinstance(exponent, int) and exponent > 1 and abs(base) > 1
    if big and (abs(base).bit_length() - 1) * exponent > MAX_INT_BITS:
        raise _too_big(base, "**", exponent)
    return base**exponent


def _mul(left: Any, right: Any) -> Any:
    lc, rc = left.__class__, right.__class__
    if lc is int and rc is int:
        if left.bit_length() + right.bit_length() > MAX_INT_BITS:
            raise _too_big(left, "*", right)
        return left * right
    if lc is float or rc is float:
        return left * right
    if isinstance(left, int) and not isinstance(right, int):
        left, right = right, left
    if isinstance(right, int) and hasattr(left, "__len__") and len(left) * max(right, 0) > MAX_SEQUENCE:
        raise ProgramError(
            f"{type(left).__name__} * {right} would hold {len(left) * right} items; at most {MAX_SEQUENCE}"
        )
    return left * right


def _lshift(value: Any, count: Any) -> Any:
    if isinstance(value, int) and isinstance(count, int) and value and value.bit_length() + count > MAX_INT_BITS:
        raise _too_big(value, "<<", count)
    return value << count


def _mod(left: Any, right: Any) -> Any:
    if isinstance(left, str | bytes):  # "%0999999999d" % 1 would build a gigabyte of text
        raise ProgramError("% formatting of text is not part of PLC programs; compute the number, store it in a tag")
    return left % right


MAX_RANGE = 1_000_000
"""The longest range a program may build (the default watchdog budget: a longer loop could never finish)."""


def bounded_range(*args: Any) -> range:
    """``range`` that refuses more items than the watchdog allows (``sum(range(10**15))`` is no loop to tick)."""
    result = range(*args)
    if len(result) > MAX_RANGE:
        raise ProgramError(f"range(...) of {len(result)} items is longer than any scan can loop (at most {MAX_RANGE})")
    return result


SAFE_OPS = {ast.Pow: "_pow", ast.Mult: "_mul", ast.LShift: "_lshift", ast.Mod: "_mod"}
"""Operators whose result can grow without bound; the CPU supplies bounded versions (see safe_math)."""
SAFE_FUNCTIONS = {"_pow": _pow, "_mul": _mul, "_lshift": _lshift, "_mod": _mod}
"""Namespace name -> bounded operator (the names the rewrite writes, see :data:`SAFE_OPS`)."""
