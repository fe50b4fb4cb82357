"""Building ``t``: the live tag object of a tag table, with its byte memories and alias links.

Where the declarations (:mod:`plcsim.tags.table`), the values (:mod:`plcsim.tags.values`) and the
aliasing (:mod:`plcsim.tags.aliasing`) meet: the S7 CPU builds its runtime when it loads a table,
tools and doctests build ``t`` alone.
"""

from __future__ import annotations

import sys
from typing import Any

from plcsim.tags.aliasing import AliasCell, MemoryLayout, area_memories, link_aliases, non_optimized_offsets
from plcsim.tags.memory import Address, ByteMemory
from plcsim.tags.table import TagTable
from plcsim.tags.types import ElementaryType
from plcsim.tags.values import PlcStruct, instantiate


def build_tags(table: TagTable, context: Any = None, layout: MemoryLayout | None = None) -> PlcStruct:
    """Create the live tag object ``t`` for a tag table (used directly in doctests and tools)."""
    t, _, _ = build_runtime(table, context, layout or MemoryLayout())
    return t


def build_runtime(
    table: TagTable, context: Any, layout: MemoryLayout
) -> tuple[PlcStruct, dict[tuple[str, int | None], ByteMemory], list[AliasCell]]:
    """Create ``t``, the byte memories and the alias links for a tag table."""
    schema = table.schema()
    t = PlcStruct(schema, "t")
    memories = area_memories(layout)
    cells: list[tuple[PlcStruct, str, Address, ElementaryType]] = []
    numbers = table.db_numbers()
    for name, entry in table.entries.items():
        value = instantiate(entry.member, name, context)
        t.__dict__[sys.intern(name)] = value  # the program's constants are interned: lookups match by identity
        if entry.address is not None:
            cells.append((t, name, entry.address, entry.member.type))  # type: ignore[arg-type]
        if entry.db is not None and not entry.db.optimized:
            number = numbers[name]
            offsets = non_optimized_offsets(entry.member.type)  # type: ignore[arg-type]
            size = max(2, _round_even(offsets.pop("__size__")[0].byte))
            memories[("DB", number)] = ByteMemory("DB", size, number)
            for key, (offset, dtype) in offsets.items():
                addr = Address("DB", offset.byte, offset.bit, offset.bits, number)
                cells.append((value, key, addr, dtype))
    aliases = link_aliases(cells, memories)
    return t, memories, aliases


def _round_even(n: int) -> int:
    return n + (n & 1)
