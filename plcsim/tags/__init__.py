"""The tag table, the S7 value types and byte-addressed memory: what every controller's I/O names stand on."""

from plcsim.tags.aliasing import AliasCell, MemoryLayout, area_memories, link_aliases, non_optimized_offsets
from plcsim.tags.runtime import build_runtime, build_tags
from plcsim.tags.table import DB, DataBlock, FBType, Tag, TagEntry, TagTable
from plcsim.tags.types import Bool, Int
from plcsim.tags.values import PlcArray, PlcStruct, copy_value, instantiate, reset_to_start, store

__all__ = [
    "Tag",
    "DataBlock",
    "DB",
    "FBType",
    "TagEntry",
    "TagTable",
    "PlcStruct",
    "PlcArray",
    "copy_value",
    "store",
    "instantiate",
    "reset_to_start",
    "AliasCell",
    "MemoryLayout",
    "area_memories",
    "link_aliases",
    "build_tags",
    "build_runtime",
    "non_optimized_offsets",
    "Bool",
    "Int",
]
