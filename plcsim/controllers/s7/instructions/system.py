"""Instructions bound to one CPU: MOVE into named outputs, the real-time clock (RD_LOC_T), jumps."""

from __future__ import annotations

import datetime as _dt
from collections.abc import Callable
from typing import Any

from plcsim.core.errors import PlcTypeError
from plcsim.tags.types import DTL, ElementaryType, StringType, StructType
from plcsim.tags.values import PlcArray, PlcStruct, store


class JumpTo(Exception):  # noqa: N818 - control flow, not an error
    """Raised by JMP to end the network and continue at the network with the label."""

    def __init__(self, label: str):
        super().__init__(label)
        self.label = label


class ReturnFromBlock(Exception):  # noqa: N818 - control flow, not an error
    """Raised by RET to end the block (the OB) for this execution."""


def JMP(label: str) -> None:
    """Jump: end this network and continue at the network carrying ``label`` (in the same OB).

    JMP runs where the program calls it, so ``if cond: JMP("lbl10")`` is LAD's ``cond -(JMP)- lbl10``
    and ``if not cond: JMP("lbl10")`` is JMPN.
    """
    raise JumpTo(label)


def RET() -> None:
    """Return: end the OB for this execution (the remaining networks do not run)."""
    raise ReturnFromBlock()


def _kind_ok(value: Any, target_type: Any) -> bool:
    if isinstance(target_type, ElementaryType):
        cls = value.__class__
        if target_type.kind == "bool":
            return cls is bool or cls.__name__ == "bool_"
        if target_type.kind in ("int", "bits", "time", "date"):
            return isinstance(value, int) and cls is not bool
        if target_type.kind == "real":
            return isinstance(value, (int, float)) and cls is not bool
        return isinstance(value, str)
    if isinstance(target_type, StringType):
        return isinstance(value, str)
    if isinstance(target_type, StructType):
        return isinstance(value, PlcStruct) and value._type is target_type
    return isinstance(value, PlcArray) and value._type.name == target_type.name


def make_move(resolve_path: Callable[[str], tuple[Any, Any]]) -> Callable[..., Any]:
    """Build MOVE bound to a CPU: ``MOVE(0, "MOTOR.SEKUNDY", "MOTOR.MINUTY")`` (one IN, several OUT)."""
    cache: dict[str, tuple[Any, Any, Any]] = {}

    def target(path: str) -> tuple[Any, Any, Any]:
        found = cache.get(path)
        if found is None:
            container, key = resolve_path(path)
            is_array = isinstance(container, PlcArray)
            mtype = container._type.element if is_array else container._type.members[key].type
            found = cache[path] = (container, key, mtype)
        return found

    def MOVE(IN: Any, *OUT: str) -> Any:
        """Copy IN to every OUT; the types of IN and the outputs must match (REAL into INT is refused)."""
        if not OUT:
            raise PlcTypeError("MOVE needs at least one output, e.g. MOVE(0, 'MOTOR.SEKUNDY')")
        for k, path in enumerate(OUT, 1):
            if not isinstance(path, str):
                raise PlcTypeError(f"MOVE: OUT{k} must name a tag, e.g. 'MOTOR.SEKUNDY', not {path!r}")
            container, key, mtype = target(path)
            if not _kind_ok(IN, mtype):
                raise PlcTypeError(
                    f"MOVE: IN is {type(IN).__name__} {IN!r} but OUT{k} {path} is {mtype.name}; "
                    f"the data types of the input and the outputs must match (use CONVERT or ROUND)"
                )
            if isinstance(container, PlcArray):
                container[key] = IN
            else:
                store(container, key, IN)
        return IN

    return MOVE


def dtl_of(moment: _dt.datetime, nanosecond: int) -> dict[str, int]:
    """The DTL members for a date and time (WEEKDAY 1 = Sunday .. 7 = Saturday)."""
    return {
        "YEAR": moment.year,
        "MONTH": moment.month,
        "DAY": moment.day,
        "WEEKDAY": moment.isoweekday() % 7 + 1,
        "HOUR": moment.hour,
        "MINUTE": moment.minute,
        "SECOND": moment.second,
        "NANOSECOND": nanosecond,
    }


def make_rd_loc_t(local_time: Callable[[], tuple[_dt.datetime, int]]) -> Callable[[], PlcStruct]:
    """Build RD_LOC_T bound to a CPU's simulated real-time clock: returns a DTL value to store."""

    def RD_LOC_T() -> PlcStruct:
        """Read the CPU's local date and time as a DTL (``t.MOTOR.DATUM_CAS = RD_LOC_T()``)."""
        moment, nanos = local_time()
        value = PlcStruct(DTL, "RD_LOC_T")
        value.__dict__.update(dtl_of(moment, nanos))
        return value

    return RD_LOC_T
