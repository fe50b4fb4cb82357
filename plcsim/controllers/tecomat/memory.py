"""The Tecomat scratchpad and its operands: byte registers X, Y, S, R, read-only data D, direct I/O U.

Every register is one byte; a word ``RW4`` is R4 (low) and R5 (high), so words overlap (RW1 shares R1
with RW0), little-endian as the manual's examples show (``WR RW4`` gives R4 = 75H, R5 = 9FH). A bit is
``R5.0``; ``low``/``high`` name the bytes of a word symbol. A long ``RL10`` is R10 (lowest) .. R13 (highest),
overlapping like words (manual §4.1.1: "typ L první byte", the number is the first byte; longs belong to
the extended instruction set, where LD, LDC, WR, WRC and PUT take them).

>>> pad = Scratchpad.sized(x=128, y=128, s=64, r=16)
>>> op = parse_address("RW4")
>>> write(pad, op, 0x9F75); pad.areas["R"][4:6].hex(), read(pad, op)
('759f', 40821)
>>> read(pad, parse_address("rw3")), read(pad, parse_address("R4.0"))
(29952, 1)
>>> write(pad, parse_address("RL8"), 0x12345678); pad.areas["R"][8:12].hex(), hex(read(pad, parse_address("RL9")))
('78563412', '0x123456')
"""

from __future__ import annotations

import re
from dataclasses import dataclass

AREAS = "XYSRDU"
WIDTH_BITS = {"bit": 1, "byte": 8, "word": 16, "long": 32}
SIZE = {"bit": 1, "byte": 1, "word": 2, "long": 4}
"""Registers (bytes) an operand of each width occupies."""
_ADDRESS = re.compile(r"^([XYSRDU])\s*([WL])?\s*(\d+)(?:\.(\d+))?$", re.IGNORECASE)
AREA_NAMES = {
    "X": "input images",
    "Y": "output images",
    "S": "system registers",
    "R": "user registers",
    "D": "program data",
    "U": "direct inputs",
}


class OperandError(ValueError):
    """An operand that is not one (the message says what the manual's syntax is)."""


@dataclass(frozen=True)
class Operand:
    """One decoded operand: an address (area, width, byte, bit) or an immediate value (area ``#``)."""

    area: str
    width: str
    index: int = 0
    bit: int = 0
    value: int = 0

    @property
    def is_immediate(self) -> bool:
        return self.area == "#"

    def __str__(self) -> str:
        if self.is_immediate:
            return str(self.value)
        if self.width == "bit":
            return f"{self.area}{self.index}.{self.bit}"
        return f"{self.area}{_PREFIX[self.width]}{self.index}"


_PREFIX = {"byte": "", "word": "W", "long": "L"}


def immediate(value: int) -> Operand:
    """An immediate operand (16 bits wide)."""
    return Operand("#", "word", value=value)


def parse_address(text: str) -> Operand:
    """``X0.5``, ``Y0``, ``SW 10``, ``rw4`` as an operand (OperandError if the text is no address)."""
    match = _ADDRESS.match(text.strip())
    if match is None:
        raise OperandError(f"{text.strip()!r} is not an address (write X0.5, Y0, R10, RW4 or SW 10)")
    area, wide, index, bit = match.group(1).upper(), (match.group(2) or "").upper(), int(match.group(3)), match.group(4)
    if wide:
        kind = "word" if wide == "W" else "long"
        if bit is not None:
            raise OperandError(
                f"{text.strip()!r}: the manual has no bit of a {kind}; name the byte, e.g. {area}{index}.0"
            )
        return Operand(area, kind, index)
    if bit is not None:
        if int(bit) > 7:
            raise OperandError(f"{text.strip()!r}: a register has bits 0..7")
        return Operand(area, "bit", index, int(bit))
    return Operand(area, "byte", index)


def low_high(operand: Operand, high: bool) -> Operand:
    """The low or high byte of a word operand (``low citac``)."""
    if operand.width != "word" or operand.is_immediate:
        raise OperandError(f"low/high take a word, not {operand}")
    return Operand(operand.area, "byte", operand.index + (1 if high else 0))


class Scratchpad:
    """The byte areas: X (input images), Y (output images), S (system), R (user), D (data), U (terminals)."""

    def __init__(self, areas: dict[str, bytearray]):
        self.areas = areas

    @classmethod
    def sized(cls, *, x: int, y: int, s: int, r: int, d: bytes = b"") -> Scratchpad:
        return cls(
            {
                "X": bytearray(x),
                "Y": bytearray(y),
                "S": bytearray(s),
                "R": bytearray(r),
                "D": bytearray(d),
                "U": bytearray(x),
            }
        )

    def check(self, operand: Operand) -> None:
        """OperandError if the operand lies outside its area."""
        if operand.is_immediate:
            return
        size = len(self.areas[operand.area])
        last = operand.index + SIZE[operand.width] - 1
        if last >= size:
            name = AREA_NAMES[operand.area]
            raise OperandError(
                f"{operand} is outside the {name}: the registers are {operand.area}0..{operand.area}{size - 1}"
            )


def read(pad: Scratchpad, operand: Operand) -> int:
    """The operand's value: a bit as 0/1, a byte, a word or a long (little-endian)."""
    if operand.is_immediate:
        return operand.value
    data = pad.areas[operand.area]
    if operand.width == "bit":
        return data[operand.index] >> operand.bit & 1
    return int.from_bytes(data[operand.index : operand.index + SIZE[operand.width]], "little")


def write(pad: Scratchpad, operand: Operand, value: int) -> None:
    """Store a bit (any non-zero value is 1), a byte, a word or a long (little-endian)."""
    data = pad.areas[operand.area]
    i = operand.index
    if operand.width == "bit":
        if value:
            data[i] |= 1 << operand.bit
        else:
            data[i] &= ~(1 << operand.bit) & 0xFF
    else:
        size = SIZE[operand.width]
        data[i : i + size] = (value & (1 << 8 * size) - 1).to_bytes(size, "little")
