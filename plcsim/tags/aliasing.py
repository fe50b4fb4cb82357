"""S7 aliasing: tags whose absolute addresses overlap (``%MW10`` and ``%M11.0``) stay consistent
through byte memory (:mod:`plcsim.tags.memory`), as on the CPU.

Only a tag that overlaps another goes through byte memory; every other tag stays a plain attribute.
The members of a non-optimized DB have absolute addresses too, laid out as classic S7 does.

>>> from plcsim.tags import Int, Tag, TagTable, build_tags, store
>>> table = TagTable()
>>> _ = table.add("CISLO", Tag("%MW10", Int))
>>> _ = table.add("LOW_BIT", Tag("%M11.0"))
>>> t = build_tags(table)
>>> store(t, "CISLO", 3)
>>> t.LOW_BIT
True
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

from plcsim.core.errors import AddressError, DeclarationError
from plcsim.tags.memory import Address, ByteMemory
from plcsim.tags.types import Bool, ElementaryType, StructType
from plcsim.tags.values import PlcStruct

# --------------------------------------------------------------------------------------------
# Overlapping addresses
# --------------------------------------------------------------------------------------------


class AliasCell:
    """A tag whose bytes overlap another tag's: its writes go through byte memory."""

    __slots__ = ("container", "key", "address", "dtype", "memory", "others")

    def __init__(self, container: PlcStruct, key: str, address: Address, dtype: ElementaryType, memory: ByteMemory):
        self.container, self.key, self.address, self.dtype, self.memory = container, key, address, dtype, memory
        self.others: list[AliasCell] = []

    def write(self, value: Any) -> None:
        """Store ``value`` (already converted) and refresh every overlapping tag."""
        self.memory.write(self.address, self.dtype, value)
        self.container.__dict__[self.key] = value
        for other in self.others:
            other.container.__dict__[other.key] = other.memory.read(other.address, other.dtype)


@dataclass
class MemoryLayout:
    """Sizes of the CPU's memory areas in bytes (defaults of an S7-1214C)."""

    inputs: int = 1024
    outputs: int = 1024
    markers: int = 8192


def area_memories(layout: MemoryLayout) -> dict[tuple[str, int | None], ByteMemory]:
    """One :class:`ByteMemory` per area."""
    return {
        ("I", None): ByteMemory("I", layout.inputs),
        ("Q", None): ByteMemory("Q", layout.outputs),
        ("M", None): ByteMemory("M", layout.markers),
    }


def link_aliases(
    cells: list[tuple[PlcStruct, str, Address, ElementaryType]], memories: dict[tuple[str, int | None], ByteMemory]
) -> list[AliasCell]:
    """Find tags whose addresses overlap and route their writes through byte memory.

    Returns the aliased cells. Tags that overlap no other tag stay plain attributes.
    """
    by_area: dict[tuple[str, int | None], list[tuple[PlcStruct, str, Address, ElementaryType]]] = {}
    for cell in cells:
        addr = cell[2]
        key = (addr.area, addr.db)
        memory = memories.get(key)
        if memory is None:
            if addr.area == "DB":
                raise AddressError(
                    f"{addr}: no non-optimized DB number {addr.db}; an optimized DB (the default) "
                    f"has no absolute addresses: use its members by name (t.DATA.X), or declare "
                    f"it with DB(..., optimized=False)"
                )
            raise AddressError(f"{addr}: no memory area for this address")
        memory.check(addr)
        by_area.setdefault(key, []).append(cell)
    linked: list[AliasCell] = []
    for key, group in by_area.items():
        group.sort(key=lambda c: (c[2].byte, c[2].bits))
        overlaps: dict[int, set[int]] = {}
        for i, a in enumerate(group):
            for j in range(i + 1, len(group)):
                b = group[j]
                if b[2].byte >= a[2].end:
                    break
                if a[2].overlaps(b[2]):
                    overlaps.setdefault(i, set()).add(j)
                    overlaps.setdefault(j, set()).add(i)
        made: dict[int, AliasCell] = {}
        for i in sorted(overlaps):
            container, name, addr, dtype = group[i]
            made[i] = AliasCell(container, name, addr, dtype, memories[key])
        for i, cell in made.items():
            cell.others = [made[j] for j in sorted(overlaps[i])]
            cell.container._aliased[cell.key] = cell
            linked.append(cell)
        # bring memory in line with the start values: later declarations win, as in byte memory
        for i in sorted(made):
            cell = made[i]
            cell.memory.write(cell.address, cell.dtype, cell.container.__dict__[cell.key])
        for cell in made.values():
            cell.container.__dict__[cell.key] = cell.memory.read(cell.address, cell.dtype)
    return linked


# --------------------------------------------------------------------------------------------
# Non-optimized data blocks
# --------------------------------------------------------------------------------------------


def non_optimized_offsets(stype: StructType) -> dict[str, tuple[Address, ElementaryType]]:
    """Classic S7 layout of a non-optimized DB (Fig. 2.8): BOOLs pack into bytes, bytes take the
    next byte, 16-bit and larger types start on an even byte.

    Returns member name -> (offset as an Address in area DB with db=None, type); the key
    ``"__size__"`` holds the total size as the byte of an Address.
    """
    out: dict[str, tuple[Address, ElementaryType]] = {}
    byte, bit = 0, 0
    for key, member in stype.members.items():
        mtype = member.type
        if not isinstance(mtype, ElementaryType):
            raise DeclarationError(
                f"{stype.name}.{key}: absolute addressing is supported for elementary members only; "
                f"make the DB optimized (the default) or flatten {mtype!r}"
            )
        if mtype.bits == 1:
            if bit == 8:
                byte, bit = byte + 1, 0
            out[key] = (Address("DB", byte, bit, 1), mtype)
            bit += 1
            continue
        if bit:
            byte, bit = byte + 1, 0
        if mtype.bits >= 16 and byte % 2:
            byte += 1
        out[key] = (Address("DB", byte, None, mtype.bits), mtype)
        byte += mtype.bits // 8
    if bit:
        byte += 1
    out["__size__"] = (Address("DB", byte, None, 8), Bool)
    return out
