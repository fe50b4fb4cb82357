"""S7 data types: elementary types with their ranges, wrap-around and conversions; ARRAY, STRUCT, DTL.

Every store into a tag goes through its type's ``coerce``: integers wrap in two's complement as the
textbook states (an INT counting past 32 767 goes on from -32 768), a REAL stored into an integer
is rounded (4.7 -> 5), a REAL is kept in single precision. A value that an S7 CPU would not convert
implicitly (a BOOL into an INT, text into a BOOL) raises :class:`PlcTypeError`.

>>> Int.coerce(32767 + 1)
-32768
>>> Int.coerce(4.7)
5
>>> Real.coerce(3.141592653589793)
3.1415927410125732
"""

from __future__ import annotations

import math
import struct
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from types import MappingProxyType
from typing import Any

from plcsim.core.errors import DeclarationError, LiteralError, PlcTypeError
from plcsim.core.literals import datetime_literal, time_ms

_F32 = struct.Struct(">f")
FLOAT32_MAX = 3.4028234663852886e38
"""The largest finite REAL; a float beyond it converts to an infinity (or to FLOAT32_MAX, if it rounds to it)."""


def _describe(value: Any) -> str:
    kind = type(value).__name__
    return f"{kind} {value!r}"


def _wrap_signed(bits: int) -> Callable[[int], int]:
    half = 1 << (bits - 1)
    mask = (1 << bits) - 1
    return lambda v: ((v + half) & mask) - half


def _wrap_unsigned(bits: int) -> Callable[[int], int]:
    mask = (1 << bits) - 1
    return lambda v: v & mask


class DataType:
    """Common base of elementary and structured types."""

    name: str
    bits: int

    def _seal(self) -> None:
        """Make the type read-only: the elementary types and ``String`` are shared by every program."""
        object.__setattr__(self, "_sealed", True)

    def __setattr__(self, name: str, value: Any) -> None:
        if getattr(self, "_sealed", False):
            raise AttributeError(f"the data type {self.name} is read-only ({name} cannot be set)")
        object.__setattr__(self, name, value)

    def default(self) -> Any:  # pragma: no cover - overridden
        raise NotImplementedError

    def __call__(self, start: Any = None, *, retain: bool = False, comment: str = "") -> Member:
        """Declare a data-block member of this type: ``DInt(0, retain=True)``."""
        return Member(self, start, retain, comment)

    def __repr__(self) -> str:
        return self.name


class ElementaryType(DataType):
    """One S7 elementary type: its size, range and how a stored value is converted.

    Attributes:
        name: the TIA name (``Int``, ``Real`` ...).
        bits: size in bits (1 for BOOL).
        kind: ``bool``, ``bits``, ``int``, ``real``, ``time``, ``char``, ``date``.
        lo, hi: the value range (None for REAL).
        fmt: the big-endian :mod:`struct` format used in byte memory (None for BOOL).
    """

    def __init__(self, name: str, bits: int, kind: str, lo: int | None, hi: int | None, fmt: str | None):
        self.name, self.bits, self.kind, self.lo, self.hi = name, bits, kind, lo, hi
        self.fmt = struct.Struct(">" + fmt) if fmt else None
        self.coerce: Callable[..., Any] = self._make_coerce()
        self._seal()

    def default(self) -> Any:
        """The zero value of the type (FALSE, 0, 0.0, T#0ms, '')."""
        return {"bool": False, "real": 0.0, "char": " "}.get(self.kind, 0)

    def _make_coerce(self) -> Callable[..., Any]:
        name, kind, lo, hi = self.name, self.kind, self.lo, self.hi

        if kind == "bool":

            def coerce_bool(value: Any, where: str = "") -> bool:
                if value is True or value is False:
                    return value
                if type(value).__name__ == "bool_":  # numpy.bool_ from a trace or a plant
                    return bool(value)
                hint = " (use True/False, or a comparison such as x > 0)" if isinstance(value, int | float) else ""
                raise PlcTypeError(f"{where or 'a Bool'} is Bool; cannot store {_describe(value)}{hint}")

            return coerce_bool

        if kind in ("int", "bits", "time", "date"):
            wrap = _wrap_signed(self.bits) if lo is not None and lo < 0 else _wrap_unsigned(self.bits)
            accepts_real = kind == "int"

            def coerce_int(value: Any, where: str = "") -> int:
                cls = value.__class__
                if cls is int:
                    return value if lo <= value <= hi else wrap(value)
                if cls is float and accepts_real:
                    if math.isfinite(value):
                        return wrap(round(value))
                    raise PlcTypeError(f"{where or 'an ' + name} is {name}; cannot store the invalid REAL {value!r}")
                if cls is str and kind == "time":
                    return wrap(time_ms(value))
                if isinstance(value, int) and cls is not bool:  # int subclasses such as numpy ints
                    return coerce_int(int(value), where)
                if cls.__name__.startswith(("int", "uint")) and hasattr(value, "item"):
                    return coerce_int(int(value), where)
                hint = ""
                if cls is bool:
                    hint = " (BOOL is not converted to a number implicitly; use 1 if x else 0)"
                elif cls is float:
                    hint = f" (REAL is not converted to {name} implicitly; use CONVERT or ROUND)"
                elif kind == "time":
                    hint = " (write a TIME as an int of ms or a literal such as '10s')"
                raise PlcTypeError(f"{where or 'a ' + name} is {name}; cannot store {_describe(value)}{hint}")

            return coerce_int

        if kind == "real":
            single = self.bits == 32

            def coerce_real(value: Any, where: str = "") -> float:
                cls = value.__class__
                if cls is float or (cls is int) or (isinstance(value, int | float) and cls is not bool):
                    f = float(value)
                    if single:
                        try:
                            return _F32.unpack(_F32.pack(f))[0]
                        except OverflowError:
                            return math.copysign(math.inf, f)
                    return f
                raise PlcTypeError(f"{where or 'a ' + name} is {name}; cannot store {_describe(value)}")

            return coerce_real

        if kind == "char":

            def coerce_char(value: Any, where: str = "") -> str:
                if isinstance(value, str) and len(value) == 1 and ord(value) < 256:
                    return value
                raise PlcTypeError(f"{where or 'a Char'} is Char; cannot store {_describe(value)} (one character)")

            return coerce_char

        raise AssertionError(kind)  # pragma: no cover

    def pack(self, value: Any) -> bytes:
        """Return the big-endian bytes of ``value`` as they sit in S7 memory."""
        if self.kind == "char":
            return value.encode("latin-1")
        return self.fmt.pack(value)

    def unpack(self, data: bytes | bytearray | memoryview) -> Any:
        """Read a value of this type from big-endian bytes."""
        if self.kind == "char":
            return bytes(data).decode("latin-1")
        return self.fmt.unpack(data)[0]


def _t(name: str, bits: int, kind: str, lo: int | None, hi: int | None, fmt: str | None) -> ElementaryType:
    return ElementaryType(name, bits, kind, lo, hi, fmt)


Bool = _t("Bool", 1, "bool", 0, 1, None)
Byte = _t("Byte", 8, "bits", 0, 0xFF, "B")
Word = _t("Word", 16, "bits", 0, 0xFFFF, "H")
DWord = _t("DWord", 32, "bits", 0, 0xFFFF_FFFF, "I")
LWord = _t("LWord", 64, "bits", 0, 0xFFFF_FFFF_FFFF_FFFF, "Q")
USInt = _t("USInt", 8, "int", 0, 255, "B")
UInt = _t("UInt", 16, "int", 0, 65_535, "H")
UDInt = _t("UDInt", 32, "int", 0, 4_294_967_295, "I")
ULInt = _t("ULInt", 64, "int", 0, 18_446_744_073_709_551_615, "Q")
SInt = _t("SInt", 8, "int", -128, 127, "b")
Int = _t("Int", 16, "int", -32_768, 32_767, "h")
DInt = _t("DInt", 32, "int", -2_147_483_648, 2_147_483_647, "i")
LInt = _t("LInt", 64, "int", -9_223_372_036_854_775_808, 9_223_372_036_854_775_807, "q")
Real = _t("Real", 32, "real", None, None, "f")
LReal = _t("LReal", 64, "real", None, None, "d")
Time = _t("Time", 32, "time", -2_147_483_648, 2_147_483_647, "i")  # milliseconds
LTime = _t("LTime", 64, "time", -9_223_372_036_854_775_808, 9_223_372_036_854_775_807, "q")  # ns
Date = _t("Date", 16, "date", 0, 65_535, "H")  # days since 1990-01-01
TimeOfDay = _t("Time_Of_Day", 32, "date", 0, 86_399_999, "I")  # ms since midnight
Char = _t("Char", 8, "char", 0, 255, None)

ELEMENTARY: dict[str, ElementaryType] = {
    t.name.lower(): t
    for t in (
        Bool,
        Byte,
        Word,
        DWord,
        LWord,
        USInt,
        UInt,
        UDInt,
        ULInt,
        SInt,
        Int,
        DInt,
        LInt,
        Real,
        LReal,
        Time,
        LTime,
        Date,
        TimeOfDay,
        Char,
    )
}
ELEMENTARY["tod"] = TimeOfDay


@dataclass(frozen=True)
class Member:
    """A member of a data block or struct: its type, start value, retain flag and comment."""

    type: DataType
    start: Any = None
    retain: bool = False
    comment: str = ""

    def start_value(self) -> Any:
        """The member's value after STOP->RUN when it is not retentive."""
        if isinstance(self.type, ElementaryType):
            if self.start is None:
                return self.type.default()
            return self.type.coerce(self.start, f"start value of a {self.type.name}")
        return self.start


class StructType(DataType):
    """A STRUCT or a PLC data type (UDT): named members of different types.

    >>> Motor = StructType("Motor", {"zapnuty": Bool, "otacky": Int(1500)})
    >>> Motor.members["otacky"].start
    1500
    """

    def __init__(self, name: str, members: Mapping[str, DataType | Member]):
        self.name = name
        self.members: Mapping[str, Member] = MappingProxyType(
            {key: as_member(spec, f"{name}.{key}") for key, spec in members.items()}
        )  # read-only: DTL is one object for every program
        self.bits = sum(m.type.bits for m in self.members.values())

    def default(self) -> Any:
        return None


class ArrayType(DataType):
    """``ARRAY[lo..hi] OF element``.

    >>> ArrayType(1, 10, Int).name
    'Array[1..10] of Int'
    """

    def __init__(self, lo: int, hi: int, element: DataType | Member):
        if not isinstance(lo, int) or not isinstance(hi, int) or hi < lo:
            raise DeclarationError(f"Array[{lo}..{hi}]: the bounds must be integers with lo <= hi")
        self.lo, self.hi = lo, hi
        member = as_member(element, "array element")
        self.element: DataType = member.type
        self.element_start = member.start
        self.name = f"Array[{lo}..{hi}] of {self.element.name}"
        self.bits = (hi - lo + 1) * self.element.bits

    def default(self) -> Any:
        return None


class StringType(DataType):
    """``STRING[n]``: text of at most ``n`` characters (S7 default 254)."""

    def __init__(self, length: int = 254):
        self.length = length
        self.name = f"String[{length}]"
        self.bits = (2 + length) * 8
        max_len = length

        def coerce_string(value: Any, where: str = "") -> str:
            if not isinstance(value, str):
                raise PlcTypeError(f"{where or 'a String'} is {self.name}; cannot store {_describe(value)}")
            return value[:max_len]

        self.coerce = coerce_string
        self._seal()

    def default(self) -> str:
        return ""


String = StringType()


def value_count(dtype: DataType) -> int:
    """How many values a tag of this type holds (an ARRAY[0..9] of a 3-member STRUCT holds 30)."""
    if isinstance(dtype, ArrayType):
        return (dtype.hi - dtype.lo + 1) * value_count(dtype.element)
    if isinstance(dtype, StructType):
        return sum(value_count(m.type) for m in dtype.members.values())
    return 1


def as_member(spec: DataType | Member, where: str) -> Member:
    """Normalise a member declaration given as a type or as ``Type(start, retain=...)``."""
    if isinstance(spec, Member):
        return spec
    if isinstance(spec, DataType):
        return Member(spec)
    raise DeclarationError(f"{where}: expected a data type such as Bool or Int(5), got {spec!r}")


DTL = StructType(
    "DTL",
    {
        "YEAR": UInt(1970),
        "MONTH": USInt(1),
        "DAY": USInt(1),
        "WEEKDAY": USInt(5),
        "HOUR": USInt(0),
        "MINUTE": USInt(0),
        "SECOND": USInt(0),
        "NANOSECOND": UDInt(0),
    },
)
"""Date and time, 12 bytes: YEAR UInt; MONTH..SECOND USInt (the real layout, errata of Fig. 4.125);
NANOSECOND UDInt. WEEKDAY counts 1 = Sunday .. 7 = Saturday (1970-01-01 was a Thursday, 5)."""


def dtl_fields(literal: str) -> dict[str, int]:
    """Return the DTL members of a ``DTL#`` literal.

    >>> dtl_fields("DTL#2022-01-25-14:49:17.016180")["WEEKDAY"]
    3
    """
    value, nanos = datetime_literal(literal)
    return {
        "YEAR": value.year,
        "MONTH": value.month,
        "DAY": value.day,
        "WEEKDAY": value.isoweekday() % 7 + 1,
        "HOUR": value.hour,
        "MINUTE": value.minute,
        "SECOND": value.second,
        "NANOSECOND": nanos,
    }


def type_by_name(name: str) -> DataType:
    """Find an elementary type by its TIA name, case-insensitively (``INT``, ``Int``, ``TOD``)."""
    key = name.strip().lower()
    if key in ELEMENTARY:
        return ELEMENTARY[key]
    if key == "dtl":
        return DTL
    if key.startswith("string"):
        inner = key[6:].strip("[] ")
        return StringType(int(inner)) if inner else String
    from plcsim.core.errors import did_you_mean

    raise LiteralError(f"unknown data type {name!r}{did_you_mean(name, [t.name for t in ELEMENTARY.values()])}")


@dataclass
class Converted:
    """Result of a checked conversion: the value and ENO (False on overflow or an invalid input)."""

    value: Any
    eno: bool = True
    notes: list[str] = field(default_factory=list)


def convert(value: Any, to: ElementaryType) -> Converted:
    """CONVERT as the textbook states: keep the low bits on integer overflow and set ENO = FALSE.

    >>> convert(65539, Int)
    Converted(value=3, eno=False, notes=[])
    >>> convert(27, Real).value
    27.0
    """
    if to.kind == "real":
        if isinstance(value, bool):
            raise PlcTypeError(f"CONVERT: a Bool cannot be converted to {to.name}")
        return Converted(to.coerce(float(value)))
    if to.kind in ("int", "bits", "time"):
        if isinstance(value, bool):
            return Converted(1 if value else 0)
        if isinstance(value, float):
            if not math.isfinite(value):
                return Converted(0, False)
            value = round(value)
        in_range = to.lo <= value <= to.hi
        return Converted(to.coerce(int(value)), in_range)
    if to.kind == "bool":
        return Converted(bool(value))
    raise PlcTypeError(f"CONVERT to {to.name} is not supported")
