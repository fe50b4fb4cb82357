"""Golden tests: absolute addresses, big-endian overlap, non-optimized DB layout (spec §3.1-§3.3).

Rules these tests pin:

* %MWa = MBa (high byte) : MB(a+1) (low byte); bit k of %MWa is %M(a + 1 - k div 8).(k mod 8);
  %MDa = MBa..MB(a+3), bit k is %M(a + 3 - k div 8).(k mod 8). The same for %I, %Q and %DB.
* Overlapping tags are one memory: a program that writes %MW10 through one tag reads the new bits
  through a %M11.x tag in the same scan; %MW0 and %MW1 share MB1.
* A non-optimized DB is laid out as Fig. 2.8: BOOLs pack into a byte, bytes take the next byte,
  16-bit and larger types start on an even byte. Its members and its absolute addresses are one
  memory. An optimized DB has no absolute addresses.
"""

from __future__ import annotations

import pytest
from hypothesis import given
from hypothesis import strategies as st

from plcsim import CPU, DB, Tag
from plcsim.core.errors import AddressError
from plcsim.tags.aliasing import non_optimized_offsets
from plcsim.tags.memory import ByteMemory, parse_address
from plcsim.tags.types import Bool, Byte, DInt, DWord, Int, Real, Word


@pytest.mark.parametrize(
    ("word", "k", "bit"),
    [
        ("%MW0", 0, "%M1.0"),
        ("%MW0", 7, "%M1.7"),
        ("%MW0", 8, "%M0.0"),
        ("%MW0", 15, "%M0.7"),
        ("%MW1", 0, "%M2.0"),
        ("%MW1", 15, "%M1.7"),
        ("%MD0", 0, "%M3.0"),
        ("%MD0", 31, "%M0.7"),
        ("%MD1", 0, "%M4.0"),
        ("%MD1", 31, "%M1.7"),
        ("%IW64", 0, "%I65.0"),
        ("%QD4", 8, "%Q6.0"),
        ("%DB5.DBW2", 0, "%DB5.DBX3.0"),
    ],
)
def test_bit_k_of_a_word_or_dword(word, k, bit):
    assert str(parse_address(word).bit_address(k)) == bit


@pytest.mark.parametrize(
    ("a", "b", "shared"),
    [
        ("%MW0", "%MW1", True),  # share MB1
        ("%MW0", "%MW2", False),  # step of 2
        ("%MD0", "%MD1", True),  # share MB1..MB3
        ("%MD0", "%MD4", False),
        ("%MW10", "%M11.0", True),
        ("%MW10", "%M12.0", False),
        ("%M0.0", "%M0.1", False),
        ("%MB1", "%MD0", True),
        ("%MW0", "%QW0", False),
        ("%DB1.DBW0", "%DB2.DBW0", False),
    ],
)
def test_overlap(a, b, shared):
    assert parse_address(a).overlaps(parse_address(b)) is shared
    assert parse_address(b).overlaps(parse_address(a)) is shared


@pytest.mark.parametrize(
    "text", ["%M10.8", "%M10", "%MW10.1", "%X1", "M", "%MW", "%DB0.DBX0.0", "%DB5.DBX0", "%DB5.DBW2.1"]
)
def test_bad_addresses(text):
    with pytest.raises(AddressError):
        parse_address(text)


def test_mw0_and_mw1_share_mb1():
    mem = ByteMemory("M", 8)
    mem.write(parse_address("%MW0"), Word, 0x1234)
    assert (mem.read(parse_address("%MB0"), Byte), mem.read(parse_address("%MB1"), Byte)) == (0x12, 0x34)
    assert mem.read(parse_address("%MW1"), Word) == 0x3400
    mem.write(parse_address("%MW1"), Word, 0xABCD)
    assert mem.read(parse_address("%MW0"), Word) == 0x12AB


def test_fig_3_89_md14_is_65539():
    mem = ByteMemory("M", 32)
    for bit in ("%M17.0", "%M17.1", "%M15.0"):  # 2#0000_0000_0000_0001_0000_0000_0000_0011
        mem.write(parse_address(bit), Bool, True)
    assert mem.read(parse_address("%MD14"), DInt) == 65_539
    assert mem.read(parse_address("%MW14"), Int) == 1 and mem.read(parse_address("%MW16"), Int) == 3


@given(st.integers(min_value=0, max_value=62), st.integers(min_value=0, max_value=0xFFFF))
def test_property_word_bytes_and_bits_are_big_endian(byte, value):
    mem = ByteMemory("M", 64)
    word = parse_address(f"%MW{byte}")
    mem.write(word, Word, value)
    assert mem.read(parse_address(f"%MB{byte}"), Byte) == value >> 8
    assert mem.read(parse_address(f"%MB{byte + 1}"), Byte) == value & 0xFF
    for k in range(16):
        assert mem.read(word.bit_address(k), Bool) == bool(value >> k & 1)
        assert word.bit_address(k) == parse_address(f"%M{byte + 1 - k // 8}.{k % 8}")


@given(st.integers(min_value=0, max_value=60), st.integers(min_value=0, max_value=0xFFFF_FFFF))
def test_property_dword_is_two_big_endian_words(byte, value):
    mem = ByteMemory("M", 64)
    mem.write(parse_address(f"%MD{byte}"), DWord, value)
    assert mem.read(parse_address(f"%MW{byte}"), Word) == value >> 16
    assert mem.read(parse_address(f"%MW{byte + 2}"), Word) == value & 0xFFFF
    for k in range(32):
        assert mem.read(parse_address(f"%M{byte + 3 - k // 8}.{k % 8}"), Bool) == bool(value >> k & 1)


OVERLAP_PROGRAM = """
CISLO = Tag("%MW10", Int)
BIT_0 = Tag("%M11.0")
BIT_2 = Tag("%M11.2")
BIT_8 = Tag("%M10.0")
SEEN_0 = Tag("%M20.0")
SEEN_2 = Tag("%M20.1")
SEEN_8 = Tag("%M20.2")
def OB1(t):
    t.CISLO = t.IW
    t.SEEN_0 = t.BIT_0          # read back in the same scan
    t.SEEN_2 = t.BIT_2
    t.SEEN_8 = t.BIT_8
"""


@pytest.mark.parametrize(
    ("value", "seen"), [(12, (False, True, False)), (256, (False, False, True)), (-1, (True,) * 3)]
)
def test_overlap_seen_from_a_program_in_the_same_scan(value, seen):
    cpu = CPU(tags={"IW": Tag("%IW64", Int), "I_LOW": Tag("%I65.0")}, program=OVERLAP_PROGRAM)
    cpu.set_input("IW", value)
    cpu.scan()
    assert (cpu.read("SEEN_0"), cpu.read("SEEN_2"), cpu.read("SEEN_8")) == seen
    assert cpu.read("I_LOW") is bool(value & 1)  # %I65.0 is bit 0 of %IW64
    assert cpu.read("%MW10") == value & 0xFFFF and cpu.read("%MB11") == value & 0xFF


def test_writing_a_bit_changes_the_word_seen_by_the_program():
    program = """
CISLO = Tag("%MW10", Int)
BIT_15 = Tag("%M10.7")
BIT_0 = Tag("%M11.0")
SEEN = Int(0)
def OB1(t):
    t.BIT_15 = True
    t.BIT_0 = True
    t.SEEN = t.CISLO
"""
    cpu = CPU(tags={"TL": Tag("%I0.0")}, program=program)
    cpu.scan()
    assert cpu.read("SEEN") == -32_767  # 16#8001 as an INT


def test_absolute_addresses_used_only_in_the_program():
    program = """
SEEN = Int(0)
def OB1(t):
    t["%MW10"] = 0x000C
    t.SEEN = t["%MB11"]
"""
    cpu = CPU(tags={"TL": Tag("%I0.0")}, program=program)
    cpu.scan()
    assert cpu.read("SEEN") == 12
    assert cpu.read("%M11.2") is True and cpu.read("%M11.3") is True and cpu.read("%M11.0") is False


# --------------------------------------------------------------------------------------------
# Data blocks (§3.3, Fig. 2.8)
# --------------------------------------------------------------------------------------------

DDD = "DDD = DB(number=5, optimized=False, A=Bool, INT_1=Int, R=Real, Z=Bool, GGG=Byte, H=Bool)\n"


def test_fig_2_8_non_optimized_offsets():
    ddd = DB(number=5, optimized=False, A=Bool, INT_1=Int, R=Real, Z=Bool, GGG=Byte, H=Bool).struct_type("DDD")
    offsets = non_optimized_offsets(ddd)
    size = offsets.pop("__size__")[0].byte
    table = {k: (f"{a.byte}.{a.bit or 0}", a.bits, t.name) for k, (a, t) in offsets.items()}
    assert table == {  # the Offset column of Fig. 2.8
        "A": ("0.0", 1, "Bool"),
        "INT_1": ("2.0", 16, "Int"),
        "R": ("4.0", 32, "Real"),
        "Z": ("8.0", 1, "Bool"),
        "GGG": ("9.0", 8, "Byte"),
        "H": ("10.0", 1, "Bool"),
    }
    assert size == 11


def test_consecutive_bools_pack_into_one_byte():
    packed = DB(optimized=False, B0=Bool, B1=Bool, B7=Bool, X=Int).struct_type("P")
    offsets = non_optimized_offsets(packed)
    assert [(a.byte, a.bit) for k, (a, _) in offsets.items() if k != "__size__"] == [(0, 0), (0, 1), (0, 2), (2, None)]


@pytest.mark.parametrize(
    ("member", "value", "address", "raw"),
    [
        ("A", True, "%DB5.DBX0.0", True),
        ("A", True, "%DB5.DBB0", 1),
        ("INT_1", 0x1234, "%DB5.DBW2", 0x1234),
        ("INT_1", -2, "%DB5.DBB3", 0xFE),
        ("R", 1.5, "%DB5.DBD4", 0x3FC0_0000),
        ("Z", True, "%DB5.DBX8.0", True),
        ("GGG", 0xAB, "%DB5.DBB9", 0xAB),
        ("H", True, "%DB5.DBX10.0", True),
    ],
)
def test_fig_2_8_members_and_absolute_addresses_are_one_memory(member, value, address, raw):
    cpu = CPU(tags={"TL": Tag("%I0.0")}, program=DDD + "def OB1(t):\n    pass\n")
    cpu.write(f"DDD.{member}", value)
    assert cpu.read(address) == raw
    assert cpu.read("%DB5.DBX0.1") is False  # DBX0.1 .. 1.7 unused


def test_db_absolute_and_symbolic_access_from_a_program():
    program = (
        DDD
        + """
SEEN_W = Int(0)
SEEN_H = Bool()
SEEN_SYM = Int(0)
def OB1(t):
    t.DDD.INT_1 = 0x1234
    t.DDD.H = True
    t.SEEN_W = t["%DB5.DBW2"]
    t.SEEN_H = t["%DB5.DBX10.0"]
    t["%DB5.DBB9"] = 7
    t.SEEN_SYM = t.DDD.GGG
"""
    )
    cpu = CPU(tags={"TL": Tag("%I0.0")}, program=program)
    cpu.scan()
    assert (cpu.read("SEEN_W"), cpu.read("SEEN_H"), cpu.read("SEEN_SYM")) == (0x1234, True, 7)


def test_optimized_db_has_no_absolute_addresses():
    program = "D = DB(number=1, X=Bool)\nY = Bool()\ndef OB1(t):\n    t.Y = t['%DB1.DBX0.0']\n"
    with pytest.raises(AddressError, match=r"%DB1\.DBX0\.0"):
        CPU(tags={"TL": Tag("%I0.0")}, program=program)
