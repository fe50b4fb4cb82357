"""Table instructions LTB, FTB, LMS, WMS (manual §7.7), over tables in T or in the scratchpad R.

A table in T is declared with ``#table``; one in R is named by its first item (``LTB R20``: a byte
table from R20; ``RW20`` a word table, ``R20.0`` a bit table) and takes its limit in A1. S1.0 is the
result flag: in range / found. Bit items are returned as masks, byte items in A0L with A0H = 0.

Choices (G10, G34, G42, §10.2): LTB pushes the item, A1 = the index (reduced modulo limit + 1 when it
was out of range, setting ``ltb_reduced_index``), A2 = the limit; FTB on a byte table compares A0L; LMS
reads at the index and then decrements it, WMS increments it and then writes (so the pair is a circular
LIFO); their index register is RWn with n the table's number (declaration order from 0, as the manual's
"register number identical with the table number"), reduced modulo limit + 1 when it holds more.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING

from plcsim.controllers.tecomat.assembly import Instruction, Table
from plcsim.controllers.tecomat.machine import TecomatRuntimeError
from plcsim.controllers.tecomat.memory import Operand

if TYPE_CHECKING:
    from plcsim.controllers.tecomat.machine import Machine

FFFF = 0xFFFF
Code = Callable[[], int]


def _items(m: Machine, arg: Table | Operand) -> tuple[Callable[[int], int], Callable[[], int] | None, str]:
    """Item reader, limit reader (None: the limit comes from A1), and the item format."""
    if isinstance(arg, Table):
        items, limit = m.tables[arg.name.lower()], arg.limit
        return items.__getitem__, (lambda: limit), arg.fmt
    data, base, bit0 = m.pad.areas["R"], arg.index, arg.bit
    size = len(data)

    def item(k: int) -> int:
        if arg.width == "bit":
            n = bit0 + k
            at = base + n // 8
            if at >= size:
                raise TecomatRuntimeError(f"the table at {arg} runs past the end of R")
            return data[at] >> (n % 8) & 1
        at = base + k * (2 if arg.width == "word" else 1)
        if at + (1 if arg.width == "word" else 0) >= size:
            raise TecomatRuntimeError(f"the table at {arg} runs past the end of R (item {k})")
        return data[at] | (data[at + 1] << 8 if arg.width == "word" else 0)

    return item, None, arg.width


def _ltb(m: Machine, index: int, instr: Instruction) -> Code:
    nxt = index + 1
    item, limit_of, fmt = _items(m, instr.arg)
    flags = m.pad.areas["S"]
    reduce = m.config.ltb_reduced_index

    def ltb() -> int:  # A0 index (A1 limit in R) -> A2 limit, A1 index, A0 item
        s = m.st
        given = s[0]
        limit = limit_of() if limit_of is not None else s[1]
        inside = given <= limit
        k = given if inside else given % (limit + 1)
        value = item(k)
        if fmt == "bit":
            value = FFFF if value else 0
        flags[1] = flags[1] & 0xFE | inside
        s.insert(0, value)
        del s[8]
        s[1] = k if reduce else given
        s[2] = limit
        return nxt

    return ltb


def _ftb(m: Machine, index: int, instr: Instruction) -> Code:
    nxt = index + 1
    item, limit_of, fmt = _items(m, instr.arg)
    flags = m.pad.areas["S"]
    mask = 0xFF if fmt == "byte" else FFFF

    def ftb() -> int:  # A0 value (A1 limit in R) -> A1 limit, A0 index or limit + 1
        s = m.st
        wanted = s[0] & mask
        limit = limit_of() if limit_of is not None else s[1]
        found = next((k for k in range(limit + 1) if item(k) == wanted), None)
        flags[1] = flags[1] & 0xFE | (found is not None)
        s[0] = limit + 1 if found is None else found
        s[1] = limit
        return nxt

    return ftb


def _index_register(m: Machine, table: Table) -> tuple[bytearray, int]:
    return m.pad.areas["R"], table.number


def _lms(m: Machine, index: int, instr: Instruction) -> Code:
    nxt, table = index + 1, instr.arg
    items, limit = m.tables[table.name.lower()], table.limit
    data, r = _index_register(m, table)
    flags = m.pad.areas["S"]

    def lms() -> int:  # push the item at the index, then the index goes down (wraps to the limit)
        k = (data[r] | data[r + 1] << 8) % (limit + 1)
        s = m.st
        s.insert(0, items[k])
        del s[8]
        k -= 1
        inside = k >= 0
        if not inside:
            k = limit
        data[r], data[r + 1] = k & 0xFF, k >> 8
        flags[1] = flags[1] & 0xFE | inside
        return nxt

    return lms


def _wms(m: Machine, index: int, instr: Instruction) -> Code:
    nxt, table = index + 1, instr.arg
    items, limit = m.tables[table.name.lower()], table.limit
    data, r = _index_register(m, table)
    flags = m.pad.areas["S"]

    def wms() -> int:  # the index goes up (wraps to 0), then A0 is written there
        k = (data[r] | data[r + 1] << 8) % (limit + 1) + 1
        inside = k <= limit
        if not inside:
            k = 0
        items[k] = m.st[0]
        data[r], data[r + 1] = k & 0xFF, k >> 8
        flags[1] = flags[1] & 0xFE | inside
        return nxt

    return wms


TABLES: dict[str, Callable[[Machine, int, Instruction], Code]] = {
    "LTB": _ltb,
    "FTB": _ftb,
    "LMS": _lms,
    "WMS": _wms,
}
