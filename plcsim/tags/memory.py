"""Absolute addresses and byte memory: %I, %Q, %M and non-optimized %DB, big-endian with overlap.

%MW10 is the word made of %MB10 (high byte) and %MB11 (low byte), so bit 0 of %MW10 is %M11.0
and %MW10 shares %MB11 with %MW11; %MD0 spans %MB0..%MB3 (bit 0 is %M3.0). Addresses are parsed
once into :class:`Address` values.

>>> a = parse_address("%MW10")
>>> (a.area, a.byte, a.bits)
('M', 10, 16)
>>> parse_address("%MW10").overlaps(parse_address("%M11.0"))
True
>>> parse_address("%MW10").bit_address(0)
Address(area='M', byte=11, bit=0, bits=1, db=None)
"""

from __future__ import annotations

import re
from dataclasses import dataclass
from functools import lru_cache
from typing import Any

from plcsim.core.errors import AddressError
from plcsim.tags.types import Bool, Byte, DataType, DWord, ElementaryType, LWord, Word

_WIDTH_LETTER = {"": 1, "X": 1, "B": 8, "W": 16, "D": 32, "L": 64}
_AREA_RE = re.compile(r"^%?(?P<area>[IQME])(?P<width>[XBWDL]?)\s*(?P<byte>\d+)(?:\.(?P<bit>\d+))?$", re.IGNORECASE)
_DB_RE = re.compile(r"^%?DB(?P<db>\d+)\.DB(?P<width>[XBWDL])\s*(?P<byte>\d+)(?:\.(?P<bit>\d+))?$", re.IGNORECASE)


@dataclass(frozen=True, order=True)
class Address:
    """A parsed absolute address.

    Attributes:
        area: ``I``, ``Q``, ``M`` or ``DB``.
        byte: the start byte.
        bit: the bit number 0..7 for a BOOL address, else None.
        bits: the width: 1, 8, 16, 32 or 64.
        db: the data block number for ``DB`` addresses.
    """

    area: str
    byte: int
    bit: int | None
    bits: int
    db: int | None = None

    @property
    def nbytes(self) -> int:
        """How many bytes the address spans (1 for a bit)."""
        return max(1, self.bits // 8)

    @property
    def end(self) -> int:
        """The first byte after the address."""
        return self.byte + self.nbytes

    def overlaps(self, other: Address) -> bool:
        """True if the two addresses share at least one bit."""
        if self.area != other.area or self.db != other.db:
            return False
        if self.byte >= other.end or other.byte >= self.end:
            return False
        if self.bit is not None and other.bit is not None:
            return self.bit == other.bit
        return True

    def bit_address(self, k: int) -> Address:
        """Return the address of bit ``k`` (0 = least significant) of this byte/word/dword."""
        if not 0 <= k < self.bits:
            raise AddressError(f"{self}: bit {k} is outside 0..{self.bits - 1}")
        if self.bits == 1:
            return self
        return Address(self.area, self.byte + self.nbytes - 1 - k // 8, k % 8, 1, self.db)

    def default_type(self) -> ElementaryType:
        """The type TIA gives an untyped absolute address of this width."""
        return {1: Bool, 8: Byte, 16: Word, 32: DWord, 64: LWord}[self.bits]

    def __str__(self) -> str:
        if self.area == "DB":
            letter = {1: "X", 8: "B", 16: "W", 32: "D", 64: "L"}[self.bits]
            suffix = f".{self.bit}" if self.bit is not None else ""
            return f"%DB{self.db}.DB{letter}{self.byte}{suffix}"
        if self.bits == 1:
            return f"%{self.area}{self.byte}.{self.bit}"
        letter = {8: "B", 16: "W", 32: "D", 64: "L"}[self.bits]
        return f"%{self.area}{letter}{self.byte}"


@lru_cache(maxsize=4096)
def parse_address(text: str) -> Address:
    """Parse ``%I0.0``, ``%QB1``, ``%MW10``, ``%MD4``, ``%DB5.DBX0.0``, ``%DB5.DBW2`` ...

    Raises :class:`AddressError` with the expected forms when the text is not an address.
    """
    if not isinstance(text, str):
        raise AddressError(f"an address must be a string such as '%M10.0', not {text!r}")
    raw = text.strip().replace(" ", "")
    m = _DB_RE.match(raw)
    if m:
        area, db = "DB", int(m["db"])
        if db < 1 or db > 65_535:
            raise AddressError(f"{text!r}: data block numbers run from 1 to 65535")
    else:
        m = _AREA_RE.match(raw)
        if not m:
            raise AddressError(
                f"{text!r} is not an absolute address; write e.g. %I0.0, %Q0.2, %M10.1, %MB4, %MW10, %MD20, "
                f"%IW64 or %DB5.DBX0.0"
            )
        area, db = m["area"].upper(), None
        if area == "E":  # German mnemonics: E = Eingang (input)
            area = "I"
    width_letter = m["width"].upper()
    bits = _WIDTH_LETTER[width_letter]
    byte = int(m["byte"])
    bit = m["bit"]
    if bits == 1:
        if bit is None:
            raise AddressError(f"{text!r}: a bit address needs a bit number, e.g. {raw}.0")
        bit_no = int(bit)
        if bit_no > 7:
            raise AddressError(f"{text!r}: bit {bit_no} does not exist; bits run from 0 to 7")
        return Address(area, byte, bit_no, 1, db)
    if bit is not None:
        raise AddressError(f"{text!r}: a {bits}-bit address has no bit number; write %{area}{width_letter}{byte}")
    return Address(area, byte, None, bits, db)


class ByteMemory:
    """A byte-addressed memory area (%I, %Q, %M or one non-optimized DB), big-endian.

    >>> m = ByteMemory("M", 16)
    >>> m.write(parse_address("%MW10"), Word, 0x1234)
    >>> hex(m.read(parse_address("%MB11"), Byte))
    '0x34'
    >>> m.read(parse_address("%M11.2"), Bool)
    True
    """

    def __init__(self, area: str, size: int, db: int | None = None):
        self.area, self.size, self.db = area, size, db
        self.data = bytearray(size)

    def check(self, address: Address) -> None:
        """Raise AddressError if the address does not lie inside this area."""
        if address.end > self.size:
            where = f"DB{self.db}" if self.db is not None else f"the %{self.area} area"
            raise AddressError(f"{address} lies outside {where}, which has bytes 0..{self.size - 1}")

    def read(self, address: Address, dtype: DataType) -> Any:
        """Read a value of ``dtype`` at ``address``."""
        self.check(address)
        if address.bits == 1:
            return bool(self.data[address.byte] >> address.bit & 1)
        return dtype.unpack(self.data[address.byte : address.end])  # type: ignore[attr-defined]

    def write(self, address: Address, dtype: DataType, value: Any) -> None:
        """Write ``value`` (already of ``dtype``) at ``address``."""
        self.check(address)
        if address.bits == 1:
            if value:
                self.data[address.byte] |= 1 << address.bit
            else:
                self.data[address.byte] &= ~(1 << address.bit) & 0xFF
            return
        self.data[address.byte : address.end] = dtype.pack(value)  # type: ignore[attr-defined]
