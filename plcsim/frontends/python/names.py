"""The names a student's program sees: its declarations, its data types and every name it may use.

A program's module level declares tags, data blocks, instances and tasks with the helpers here
(``Tag``, ``DB``, ``CyclicInterrupt``, ``label``, ``Array``, ``UDT`` ...); its networks see the data
types, ``TIME``, the instructions and the allowed builtins. The subset check, the evaluation of the
module level, the runtime namespace and the students' reference page all read these tables.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

from plcsim.controllers.s7.instructions import CPU_BOUND, FB_TYPES, PURE_INSTRUCTIONS
from plcsim.controllers.s7.profile import DEFAULT_INTERRUPT_PRIORITY
from plcsim.core.errors import DeclarationError
from plcsim.core.literals import time_ms
from plcsim.tags import types as plc_types
from plcsim.tags.table import DB, Tag
from plcsim.tags.types import ArrayType, DataType, Member, StructType


def label(name: str) -> Callable[[Callable[..., Any]], Callable[..., Any]]:
    """Mark a network as a jump target: ``@label("lbl10")`` (one label per network, unique per OB)."""
    if not isinstance(name, str) or not name:
        raise DeclarationError(f"a label must be a non-empty string, not {name!r}")

    def mark(func: Callable[..., Any]) -> Callable[..., Any]:
        func.plc_label = name  # type: ignore[attr-defined]
        return func

    return mark


@dataclass(frozen=True)
class CyclicInterrupt:
    """A cyclic-interrupt OB (OB30..OB38): its networks, period, phase and priority.

    ``OB30 = CyclicInterrupt([read_button, count], period="1s")``; the first call comes at the
    STOP->RUN instant plus the phase.
    """

    networks: Any
    period: str | int | None = None
    """None: the hardware configuration's period (``CPUConfig.periods``), else 100 ms."""
    phase: str | int = "0ms"
    priority: int = DEFAULT_INTERRUPT_PRIORITY
    duration: str | int | None = None


def Array(lo: int, hi: int, element: DataType | Member) -> ArrayType:
    """``Array[lo..hi] of element`` for DB members: ``Array(0, 3, Int)``."""
    return ArrayType(lo, hi, element)


def Struct(**members: DataType | Member) -> StructType:
    """An anonymous STRUCT for a DB member: ``Struct(OBS=Bool, POCET=Int)``."""
    return StructType("Struct", members)


def UDT(**members: DataType | Member) -> StructType:
    """A PLC data type (named after the variable it is assigned to): ``NASA = UDT(OBS=Bool)``."""
    return StructType("UDT", members)


def TIME(literal: str) -> int:
    """A TIME literal as milliseconds, for comparisons with ET: ``t.T1.ET > TIME("500ms")``."""
    return time_ms(literal)


TYPE_NAMES: dict[str, Any] = {
    **{t.name: t for t in plc_types.ELEMENTARY.values()},
    "TOD": plc_types.TimeOfDay,
    "String": plc_types.String,
    "DTL": plc_types.DTL,
}
"""Data types: declared at module level, and named in networks (``CONVERT(x, Int)``)."""

DECLARATION_ONLY: dict[str, Any] = {
    "Array": Array,
    "Struct": Struct,
    "UDT": UDT,
    "Tag": Tag,
    "DB": DB,
    "CyclicInterrupt": CyclicInterrupt,
    "label": label,
    **FB_TYPES,
}
"""Names that declare something; a network cannot use them (it sees the declared tag as t.NAME)."""

DECLARATION_NAMES: dict[str, Any] = {**TYPE_NAMES, **DECLARATION_ONLY, "TIME": TIME}
"""Names a program may use at module level to declare tags, DBs, instances and tasks."""

PROGRAM_NAMES = set(DECLARATION_NAMES) | set(PURE_INSTRUCTIONS) | CPU_BOUND
"""Every name a program sees besides its own and the allowed builtins."""

__all__ = [
    "Array",
    "CyclicInterrupt",
    "DECLARATION_NAMES",
    "DECLARATION_ONLY",
    "PROGRAM_NAMES",
    "Struct",
    "TIME",
    "TYPE_NAMES",
    "UDT",
    "label",
]
