"""Golden tests: S7 data types, conversions, math boxes and literals (spec §2, §4.2, §4.3).

Rules these tests pin:

* Every store converts to the tag's type: integers wrap in two's complement (no saturation, no
  fault), a REAL stored into an integer is rounded (4.7 -> 5; ties to even), REAL is float32 and
  LREAL float64; a BOOL is never converted to a number implicitly, nor a number to a BOOL.
* CONVERT keeps the low bits on integer overflow and reports ENO = FALSE (DINT 65 539 -> INT 3).
* DIV truncates toward zero on integers (11 / 3 = 3); MOD's sign follows the dividend.
* Literals: 2#, 8#, 16# bases with ``_`` separators, typed prefixes (W#16#...), TIME literals
  ``T#1s500ms`` as signed ms, formatted as TIA shows them (``T#1s_500ms``).
* DTL: YEAR UInt, MONTH..SECOND USInt, NANOSECOND UDInt; start DTL#1970-01-01-00:00:00 with WEEKDAY 5;
  WEEKDAY counts 1 = Sunday .. 7 = Saturday.
"""

from __future__ import annotations

import math

import pytest
from hypothesis import given
from hypothesis import strategies as st

from plcsim import CPU, Tag
from plcsim.controllers.s7.instructions.arithmetic import (
    ACOS,
    ASIN,
    ATAN,
    CEIL,
    CONVERT,
    DIV,
    FLOOR,
    FRAC,
    IN_RANGE,
    LIMIT,
    MOD,
    NORM_X,
    OUT_RANGE,
    ROUND,
    SCALE_X,
    SQRT,
    TRUNC,
)
from plcsim.core.errors import LiteralError, PlcTypeError
from plcsim.core.literals import duration_ns, format_time_ms, integer_literal, time_ms
from plcsim.tags.types import (
    DTL,
    Bool,
    Byte,
    DInt,
    DWord,
    Int,
    LInt,
    LReal,
    LWord,
    Real,
    SInt,
    Time,
    UDInt,
    UInt,
    ULInt,
    USInt,
    Word,
    convert,
    dtl_fields,
)

INTEGER_TYPES = [
    (SInt, -128, 127),
    (Int, -32_768, 32_767),
    (DInt, -2_147_483_648, 2_147_483_647),
    (LInt, -(2**63), 2**63 - 1),
    (USInt, 0, 255),
    (UInt, 0, 65_535),
    (UDInt, 0, 4_294_967_295),  # erratum: the table prints 4 294 967 296
    (ULInt, 0, 2**64 - 1),
    (Byte, 0, 0xFF),
    (Word, 0, 0xFFFF),
    (DWord, 0, 0xFFFF_FFFF),
    (LWord, 0, 2**64 - 1),
    (Time, -2_147_483_648, 2_147_483_647),
]
IDS = [t.name for t, _, _ in INTEGER_TYPES]


@pytest.mark.parametrize(("dtype", "lo", "hi"), INTEGER_TYPES, ids=IDS)
def test_integer_type_ranges_and_wrap(dtype, lo, hi):
    assert (dtype.lo, dtype.hi) == (lo, hi)
    assert dtype.coerce(hi) == hi and dtype.coerce(lo) == lo
    assert dtype.coerce(hi + 1) == lo  # past the maximum comes the minimum
    assert dtype.coerce(lo - 1) == hi
    assert dtype.bits == (hi - lo + 1).bit_length() - 1


@pytest.mark.parametrize(("dtype", "lo", "hi"), INTEGER_TYPES, ids=IDS)
def test_bytes_are_big_endian_twos_complement(dtype, lo, hi):
    n = dtype.bits // 8
    assert dtype.pack(lo) == lo.to_bytes(n, "big", signed=lo < 0)
    assert dtype.pack(hi) == hi.to_bytes(n, "big", signed=lo < 0)
    assert dtype.unpack(dtype.pack(-1 if lo < 0 else hi)) == (-1 if lo < 0 else hi)


@given(st.sampled_from(INTEGER_TYPES), st.integers(min_value=-(2**70), max_value=2**70))
def test_property_integer_wrap_is_twos_complement(spec, value):
    dtype, lo, hi = spec
    span = hi - lo + 1
    expected = (value - lo) % span + lo
    assert dtype.coerce(value) == expected
    raw = value & (span - 1)  # the low bits kept in memory
    assert dtype.unpack(raw.to_bytes(dtype.bits // 8, "big")) == expected


def test_int_statements_of_section_2_3():
    program = """
CISLO = Int(32767)
R = Real(4.7)
D = DInt(65539)
OUT = Int(0)
ENO = Bool()
def OB1(t):
    t.CISLO += 1                 # ADD: 32 767 + 1 -> -32 768
    t.OUT = t.R                  # implicit REAL -> INT rounds: 5
    v, eno = CONVERT(t.D, Int, with_eno=True)
    t.ENO = eno
"""
    cpu = CPU(tags={"TL": Tag("%I0.0")}, program=program)
    cpu.scan()
    assert (cpu.read("CISLO"), cpu.read("OUT"), cpu.read("ENO")) == (-32_768, 5, False)
    cpu.scan()
    assert cpu.read("CISLO") == -32_767  # and keeps counting up


def test_int_plus_2_wraps_to_negative_and_keeps_counting():
    cpu = CPU(tags={"TL": Tag("%I0.0")}, program="CISLO = Int(32766)\ndef OB1(t):\n    t.CISLO = t.CISLO + 2\n")
    cpu.scan(3)
    assert cpu.read("CISLO") == -32_764


@pytest.mark.parametrize(
    ("value", "stored"),
    [(4.2, 4), (4.7, 5), (13 + 4.7, 18), (-4.7, -5), (10.5, 10), (11.5, 12), (26.49, 26)],
)
def test_implicit_real_to_int_rounds(value, stored):
    assert Int.coerce(value) == stored


def test_add_typed_real_with_an_int_output_stores_18():
    program = "IN1 = Int(13)\nOUT = Int(0)\ndef OB1(t):\n    t.OUT = t.IN1 + 4.7\n"
    cpu = CPU(tags={"TL": Tag("%I0.0")}, program=program)
    cpu.scan()
    assert cpu.read("OUT") == 18


def test_conv_dint_to_int_keeps_the_low_16_bits_and_eno_false():
    assert CONVERT(65_539, Int, with_eno=True) == (3, False)
    assert CONVERT(0b0000_0000_0000_0001_0000_0000_0000_0011, Int) == 3
    assert CONVERT(1000, Int, with_eno=True) == (1000, True)
    assert convert(27, Real).value == 27.0 and convert(27, Real).eno is True
    assert CONVERT(-1, UInt, with_eno=True) == (65_535, False)


def test_real_is_float32_and_lreal_float64():
    pi32 = Real.coerce(math.pi)
    assert f"{pi32:.7g}" == "3.141593"  # "3.141592653589793... is stored and shown as 3.141593"
    assert pi32 != math.pi and LReal.coerce(math.pi) == math.pi
    assert f"{Real.coerce(math.sin(pi32)):.6E}" == "-8.742278E-08"
    assert Real.coerce(1e39) == math.inf
    assert Real.coerce(16_777_217) == 16_777_216.0  # 24-bit mantissa


def test_sin_of_real_and_lreal_pi_in_a_program():
    program = """
M = DB(PI=Real(3.141592653589793), LPI=LReal(3.14159265358979), S=Real(), LS=LReal())
def OB1(t):
    t.M.S = SIN(t.M.PI)
    t.M.LS = SIN(t.M.LPI)
"""
    cpu = CPU(tags={"TL": Tag("%I0.0")}, program=program)
    cpu.scan()
    assert f"{cpu.read('M.S'):.6E}" == "-8.742278E-08"
    assert f"{cpu.read('M.LS'):.14E}" == "3.23108914886517E-15"


@pytest.mark.parametrize(
    ("dtype", "value"),
    [(Bool, 1), (Bool, 0), (Bool, "TRUE"), (Int, True), (Int, "5"), (Word, 1.5), (Time, 1.5), (Real, True)],
)
def test_no_implicit_conversion_between_bool_and_numbers(dtype, value):
    with pytest.raises(PlcTypeError, match=dtype.name):
        dtype.coerce(value, "X")


def test_time_accepts_literals_and_wraps_as_signed_ms():
    assert Time.coerce("T#1s500ms") == 1500
    assert Time.coerce("T#24d20h31m23s648ms") == -2_147_483_648


# --------------------------------------------------------------------------------------------
# Math and comparison boxes (§4.2-§4.4)
# --------------------------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("box", "args", "expected"),
    [
        pytest.param(DIV, (11, 3), 3, id="DIV-11/3-truncates"),
        pytest.param(DIV, (-11, 3), -3, id="DIV-toward-zero"),
        pytest.param(DIV, (11.0, 3.0), 11.0 / 3.0, id="DIV-real"),
        pytest.param(MOD, (7, 2), 1, id="MOD"),
        pytest.param(MOD, (-7, 2), -1, id="MOD-sign-of-dividend"),
        pytest.param(MOD, (7, -2), 1, id="MOD-positive-dividend"),
        pytest.param(ROUND, (26.8,), 27, id="ROUND-26.8"),
        pytest.param(ROUND, (26.49,), 26, id="ROUND-26.49"),
        pytest.param(ROUND, (10.5,), 10, id="ROUND-ties-even-10.5"),
        pytest.param(ROUND, (11.5,), 12, id="ROUND-ties-even-11.5"),
        pytest.param(CEIL, (12.34,), 13, id="CEIL"),
        pytest.param(FLOOR, (99.99,), 99, id="FLOOR"),
        pytest.param(FLOOR, (-1.2,), -2, id="FLOOR-negative"),
        pytest.param(TRUNC, (-1.2,), -1, id="TRUNC"),
        pytest.param(NORM_X, (0.0, 50.0, 100.0), 0.5, id="NORM_X"),
        pytest.param(NORM_X, (0.0, 110.0, 100.0), 1.1, id="NORM_X-unclamped"),
        pytest.param(SCALE_X, (0.0, 0.5, 100.0), 50.0, id="SCALE_X"),
        pytest.param(SCALE_X, (0.0, 1.5, 100.0), 150.0, id="SCALE_X-unclamped"),
        pytest.param(SQRT, (16.0,), 4.0, id="SQRT"),
        pytest.param(SQRT, (0.0,), 0.0, id="SQRT-0"),
        pytest.param(ASIN, (1.0,), math.pi / 2, id="ASIN"),
        pytest.param(ACOS, (1.0,), 0.0, id="ACOS"),
        pytest.param(IN_RANGE, (2, 0, 8), False, id="IN_RANGE-0"),
        pytest.param(IN_RANGE, (2, 8, 8), True, id="IN_RANGE-inclusive"),
        pytest.param(OUT_RANGE, (2, 9, 8), True, id="OUT_RANGE"),
        pytest.param(OUT_RANGE, (2, 2, 8), False, id="OUT_RANGE-bound"),
        pytest.param(LIMIT, (0, 150, 100), 100, id="LIMIT"),
    ],
)
def test_math_boxes(box, args, expected):
    assert box(*args) == expected


def test_invalid_floats_and_precision():
    assert math.isnan(SQRT(-1.0)) and math.isnan(ASIN(1.5))
    assert ATAN(999_999.0) == pytest.approx(math.pi / 2, abs=1e-5)
    frac = FRAC(Real.coerce(123.4567))
    assert frac != 0.4567 and frac == pytest.approx(0.4567, abs=1e-5)  # "does not match" the visible fraction
    with pytest.raises(ZeroDivisionError):
        DIV(1, 0)


# --------------------------------------------------------------------------------------------
# Literals (§2.2)
# --------------------------------------------------------------------------------------------


@pytest.mark.parametrize(
    "text", ["2#1111111111111111", "2#1111_1111_1111_1111", "8#177777", "65535", "16#FFFF", "16#ffff"]
)
def test_the_four_literals_of_section_2_4_are_equal(text):
    assert integer_literal(text) == (65_535, None)


@pytest.mark.parametrize(
    ("text", "value", "type_name"),
    [
        ("2#0000_0000_0000_1100", 12, None),
        ("16#000C", 12, None),
        ("W#16#000C", 12, "Word"),
        ("B#16#FF", 255, "Byte"),
        ("DW#16#FFFF_FFFF", 4_294_967_295, "DWord"),
        ("LW#16#0000_0000_0000_0001", 1, "LWord"),
        ("INT#-5", -5, "INT"),
    ],
)
def test_typed_and_grouped_literals(text, value, type_name):
    assert integer_literal(text) == (value, type_name)


@pytest.mark.parametrize("text", ["16#FFFG", "2#102", "8#9", "", "0x10"])
def test_bad_integer_literals(text):
    with pytest.raises(LiteralError):
        integer_literal(text)


@pytest.mark.parametrize(
    ("text", "ms"),
    [
        ("T#0ms", 0),
        ("T#0s", 0),
        ("T#1s500ms", 1500),
        ("t#1s_500ms", 1500),
        ("TIME#2h", 7_200_000),
        ("T#1h2m3s4ms", 3_723_004),
        ("T#-24d20h31m23s648ms", -2_147_483_648),
        ("T#+24d20h31m23s647ms", 2_147_483_647),
        ("10s", 10_000),
        ("1.5s", 1500),
        ("250ms", 250),
    ],
)
def test_time_literals(text, ms):
    assert time_ms(text) == ms


@pytest.mark.parametrize(
    ("ms", "text"),
    [(0, "T#0ms"), (1500, "T#1s_500ms"), (-2_147_483_648, "T#-24d_20h_31m_23s_648ms"), (4_324, "T#4s_324ms")],
)
def test_time_formatting(ms, text):
    assert format_time_ms(ms) == text


@pytest.mark.parametrize("text", ["T#1ms1s", "T#5x", "T#", "T#1.5ms", "T#1s 2"])
def test_bad_time_literals(text):
    with pytest.raises(LiteralError):
        time_ms(text)


def test_ltime_literal_in_ns():
    assert duration_ns("LT#5us") == 5_000


@given(st.integers(min_value=Time.lo, max_value=Time.hi))
def test_property_time_literal_round_trip(ms):
    assert time_ms(format_time_ms(ms)) == ms


@given(st.integers(min_value=0, max_value=2**64 - 1))
def test_property_integer_literal_round_trip(value):
    assert integer_literal(f"16#{value:X}") == (value, None)
    assert integer_literal(f"8#{value:o}") == (value, None)
    grouped = "_".join(f"{value:b}"[::-1][i : i + 4][::-1] for i in range(0, len(f"{value:b}"), 4)[::-1])
    assert integer_literal(f"2#{grouped}") == (value, None)


# --------------------------------------------------------------------------------------------
# DTL
# --------------------------------------------------------------------------------------------


def test_dtl_member_types_and_start_values():
    types = {k: m.type.name for k, m in DTL.members.items()}
    assert types == {
        "YEAR": "UInt",
        "MONTH": "USInt",
        "DAY": "USInt",
        "WEEKDAY": "USInt",
        "HOUR": "USInt",
        "MINUTE": "USInt",
        "SECOND": "USInt",
        "NANOSECOND": "UDInt",
    }
    cpu = CPU(tags={"TL": Tag("%I0.0")}, program="MOTOR = DB(DATUM_CAS=DTL)\ndef OB1(t):\n    pass\n")
    starts = {k: cpu.read(f"MOTOR.DATUM_CAS.{k}") for k in DTL.members}
    assert starts == {
        "YEAR": 1970,
        "MONTH": 1,
        "DAY": 1,
        "WEEKDAY": 5,
        "HOUR": 0,
        "MINUTE": 0,
        "SECOND": 0,
        "NANOSECOND": 0,
    }
    assert dtl_fields("DTL#1970-01-01-00:00:00") == starts


def test_dtl_monitored_example_fig_4_128():
    assert dtl_fields("DTL#2022-01-25-14:49:17.016180") == {
        "YEAR": 2022,
        "MONTH": 1,
        "DAY": 25,
        "WEEKDAY": 3,
        "HOUR": 14,
        "MINUTE": 49,
        "SECOND": 17,
        "NANOSECOND": 16_180_000,
    }


@pytest.mark.parametrize(
    ("day", "weekday"),
    [(23, 1), (24, 2), (25, 3), (26, 4), (27, 5), (28, 6), (29, 7), (30, 1)],
    ids=["Sun", "Mon", "Tue", "Wed", "Thu", "Fri", "Sat", "Sun-again"],
)
def test_dtl_weekday_counts_from_sunday(day, weekday):
    assert dtl_fields(f"DTL#2022-01-{day}-12:00:00")["WEEKDAY"] == weekday
