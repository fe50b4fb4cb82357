"""Math, comparison and conversion boxes with S7 semantics where they differ from Python's.

Python's ``+ - *`` and comparisons already behave like ADD, SUB, MUL and CMP once the result is stored
into a typed tag (which wraps). The boxes here are the ones Python would get wrong:

* ``DIV(11, 3) == 3`` and ``DIV(-7, 2) == -3``: integer division truncates toward zero (Python's ``//`` floors).
* ``MOD(-7, 2) == -1``: the remainder takes the sign of the dividend (Python's ``%`` takes the divisor's).
* ``ROUND(10.5) == 10``: ties go to even.
* ``NORM_X``/``SCALE_X`` are not limited; ``SCALE``/``UNSCALE`` use the analog range 0..27 648.

>>> DIV(11, 3), DIV(11.0, 3.0)
(3, 3.6666666666666665)
>>> IN_RANGE(2, 8, 8), OUT_RANGE(2, 0, 8)
(True, True)
>>> NORM_X(0.0, 110.0, 100.0), SCALE_X(0.0, 0.5, 100.0)
(1.1, 50.0)
"""

from __future__ import annotations

import math
import struct
from typing import Any

from plcsim.core.errors import PlcTypeError
from plcsim.tags.types import ElementaryType, convert

ANALOG_MAX = 27_648
"""Siemens nominal analog range: 0..27 648 unipolar, -27 648..27 648 bipolar."""

_F32 = struct.Struct(">f")


def _number(value: Any, box: str) -> int | float:
    if value.__class__ in (int, float):
        return value
    if isinstance(value, (int, float)) and not isinstance(value, bool):
        return value
    raise PlcTypeError(f"{box}: operands must be numbers, not {value!r}")


def _integers(a: Any, b: Any) -> bool:
    return a.__class__ is int and b.__class__ is int


def DIV(in1: Any, in2: Any) -> int | float:
    """IN1 / IN2: integers truncate toward zero (11/3 = 3); REAL divides (division by 0.0 gives ±INF or NaN).

    Integer division by zero raises ZeroDivisionError, which stops the CPU with the network named.
    """
    a, b = _number(in1, "DIV"), _number(in2, "DIV")
    if _integers(a, b):
        if b == 0:
            raise ZeroDivisionError("DIV: integer division by zero")
        q = abs(a) // abs(b)
        return q if (a >= 0) == (b >= 0) else -q
    if b == 0:
        return math.copysign(math.inf, a) * math.copysign(1.0, b) if a else math.nan
    return a / b


def MOD(in1: int, in2: int) -> int:
    """Integer remainder; its sign follows the dividend (MOD(-7, 2) = -1)."""
    a, b = _number(in1, "MOD"), _number(in2, "MOD")
    if not _integers(a, b):
        raise PlcTypeError("MOD works on integers only")
    if b == 0:
        raise ZeroDivisionError("MOD: division by zero")
    return a - DIV(a, b) * b  # type: ignore[operator]


def IN_RANGE(MIN: Any, VAL: Any, MAX: Any) -> bool:
    """TRUE if MIN <= VAL <= MAX (inclusive)."""
    return MIN <= VAL <= MAX


def OUT_RANGE(MIN: Any, VAL: Any, MAX: Any) -> bool:
    """TRUE if VAL < MIN or VAL > MAX."""
    return VAL < MIN or VAL > MAX


def LIMIT(MN: Any, IN: Any, MX: Any) -> Any:
    """IN limited to MN..MX."""
    return MN if IN < MN else MX if IN > MX else IN


def ROUND(value: float) -> int:
    """Round to the nearest integer, ties to even (ROUND(10.5) = 10, ROUND(11.5) = 12)."""
    return round(_number(value, "ROUND"))


def CEIL(value: float) -> int:
    """The next integer up (CEIL(12.34) = 13)."""
    return math.ceil(_number(value, "CEIL"))


def FLOOR(value: float) -> int:
    """The next integer down (FLOOR(-1.2) = -2)."""
    return math.floor(_number(value, "FLOOR"))


def TRUNC(value: float) -> int:
    """The integer part, toward zero (TRUNC(-1.2) = -1)."""
    return math.trunc(_number(value, "TRUNC"))


def FRAC(value: float) -> float:
    """The fractional part (FRAC(123.4567) = 0.4567, up to REAL precision)."""
    v = _number(value, "FRAC")
    return v - math.trunc(v)


def NORM_X(MIN: float, VALUE: float, MAX: float) -> float:
    """(VALUE - MIN) / (MAX - MIN), not limited to 0..1 (110 in 0..100 gives 1.1)."""
    if MAX == MIN:
        raise ZeroDivisionError("NORM_X: MIN and MAX are equal")
    return (VALUE - MIN) / (MAX - MIN)


def SCALE_X(MIN: float, VALUE: float, MAX: float) -> float:
    """VALUE * (MAX - MIN) + MIN, not limited (0.5 into 0..100 gives 50.0)."""
    return VALUE * (MAX - MIN) + MIN


def SCALE(IN: int, HI_LIM: float, LO_LIM: float, BIPOLAR: bool = False) -> float:
    """Legacy SCALE (S7-300/1500): analog value 0..27 648 (or ±27 648) to LO_LIM..HI_LIM."""
    if BIPOLAR:
        return (IN + ANALOG_MAX) / (2 * ANALOG_MAX) * (HI_LIM - LO_LIM) + LO_LIM
    return IN / ANALOG_MAX * (HI_LIM - LO_LIM) + LO_LIM


def UNSCALE(IN: float, HI_LIM: float, LO_LIM: float, BIPOLAR: bool = False) -> int:
    """Legacy UNSCALE: LO_LIM..HI_LIM back to 0..27 648 (or ±27 648), rounded."""
    fraction = (IN - LO_LIM) / (HI_LIM - LO_LIM)
    return round(fraction * 2 * ANALOG_MAX - ANALOG_MAX) if BIPOLAR else round(fraction * ANALOG_MAX)


def CONVERT(value: Any, to: ElementaryType, *, with_eno: bool = False) -> Any:
    """CONV to the type on the box: an integer overflow keeps the low bits (DINT 65 539 -> INT 3).

    With ``with_eno=True`` returns ``(value, ENO)``, ENO being FALSE after an overflow.
    """
    if not isinstance(to, ElementaryType):
        raise PlcTypeError(f"CONVERT needs a target type such as Int or Real, not {to!r}")
    result = convert(value, to)
    return (result.value, result.eno) if with_eno else result.value


def _real(x: float) -> float:
    return _F32.unpack(_F32.pack(x))[0]


def SQR(x: float) -> float:
    """IN squared."""
    return _number(x, "SQR") ** 2


def SQRT(x: float) -> float:
    """Square root; a negative input gives an invalid number (NaN)."""
    x = _number(x, "SQRT")
    return math.sqrt(x) if x >= 0 else math.nan


def LN(x: float) -> float:
    """Natural logarithm; IN <= 0 gives NaN."""
    x = _number(x, "LN")
    return math.log(x) if x > 0 else math.nan


def EXP(x: float) -> float:
    """e to the power IN."""
    return math.exp(_number(x, "EXP"))


def EXPT(base: float, exponent: float) -> float:
    """IN1 to the power IN2."""
    return float(_number(base, "EXPT")) ** _number(exponent, "EXPT")


def SIN(x: float) -> float:
    """Sine of an angle in radians (a REAL result once stored: SIN(REAL pi) = -8.742278E-08)."""
    return math.sin(_number(x, "SIN"))


def COS(x: float) -> float:
    """Cosine of an angle in radians."""
    return math.cos(_number(x, "COS"))


def TAN(x: float) -> float:
    """Tangent of an angle in radians."""
    return math.tan(_number(x, "TAN"))


def ASIN(x: float) -> float:
    """Arc sine; IN outside -1..1 gives NaN."""
    x = _number(x, "ASIN")
    return math.asin(x) if -1.0 <= x <= 1.0 else math.nan


def ACOS(x: float) -> float:
    """Arc cosine; IN outside -1..1 gives NaN."""
    x = _number(x, "ACOS")
    return math.acos(x) if -1.0 <= x <= 1.0 else math.nan


def ATAN(x: float) -> float:
    """Arc tangent, in (-pi/2, pi/2)."""
    return math.atan(_number(x, "ATAN"))


def REAL(x: float) -> float:
    """A value rounded to single precision, as a REAL tag holds it (REAL(3.141592653589793) = 3.1415927...)."""
    return _real(float(_number(x, "REAL")))


MATH_FUNCTIONS = {
    f.__name__: f
    for f in (
        DIV,
        MOD,
        IN_RANGE,
        OUT_RANGE,
        LIMIT,
        ROUND,
        CEIL,
        FLOOR,
        TRUNC,
        FRAC,
        NORM_X,
        SCALE_X,
        SCALE,
        UNSCALE,
        CONVERT,
        SQR,
        SQRT,
        LN,
        EXP,
        EXPT,
        SIN,
        COS,
        TAN,
        ASIN,
        ACOS,
        ATAN,
        REAL,
    )
}
