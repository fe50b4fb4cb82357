"""The S7 values: the live objects a program reads and writes, and the one converting store.

A program sees one object, ``t``, whose attributes are the tags: ``t.S1`` is a BOOL input,
``t.DATA.D1_POZ1_OBS`` a member of the global DB ``DATA``, ``t.TON_A`` a timer instance. Reading a
tag is a plain attribute read; every store is converted to the tag's S7 type (see
:mod:`plcsim.tags.types`). A member whose bytes overlap another tag's is written through its alias cell
(:mod:`plcsim.tags.aliasing`), found in the struct's ``_aliased``. These reads and stores run on every
scan, hence kept to plain attribute and dict accesses.
"""

from __future__ import annotations

import sys
from collections.abc import Iterator, Mapping
from typing import Any

from plcsim.core.errors import DeclarationError, PlcTypeError, UnknownTagError, did_you_mean
from plcsim.tags.table import FBType
from plcsim.tags.types import ArrayType, ElementaryType, Member, StringType, StructType, dtl_fields

# --------------------------------------------------------------------------------------------
# Live objects
# --------------------------------------------------------------------------------------------


class PlcStruct:
    """A live struct, data block or the root tag object: members are attributes.

    Reads are plain attribute reads; :func:`store` converts and writes.
    """

    __slots__ = ("_type", "_path", "_aliased", "__dict__")

    def __init__(self, stype: StructType, path: str):
        object.__setattr__(self, "_type", stype)
        object.__setattr__(self, "_path", path)
        object.__setattr__(self, "_aliased", {})

    def __getattr__(self, name: str) -> Any:  # only called when the member does not exist
        if name.startswith("__"):
            raise AttributeError(name)
        raise UnknownTagError(_unknown(self, name))

    def __setattr__(self, name: str, value: Any) -> None:
        store(self, name, value)

    def __getitem__(self, name: str) -> Any:
        if name in self.__dict__:
            return self.__dict__[name]
        raise UnknownTagError(_unknown(self, name))

    def __setitem__(self, name: str, value: Any) -> None:
        store(self, name, value)

    def __dir__(self) -> list[str]:
        return list(self.__dict__)

    def __repr__(self) -> str:
        inner = ", ".join(f"{k}={v!r}" for k, v in self.__dict__.items())
        return f"<{self._path}: {inner}>"


def _unknown(obj: PlcStruct, name: str) -> str:
    where = "no tag" if obj._path == "t" else f"{obj._path} has no member"
    return f"{where} {name!r}{did_you_mean(name, obj._type.members)}"


class PlcArray:
    """A live ``ARRAY[lo..hi] OF T``: indexed with the declared bounds, stores converted."""

    __slots__ = ("_type", "_path", "_items", "_lo", "_coerce")

    def __init__(self, atype: ArrayType, path: str, items: list[Any]):
        self._type, self._path, self._items, self._lo = atype, path, items, atype.lo
        element = atype.element
        self._coerce = element.coerce if isinstance(element, (ElementaryType, StringType)) else None

    def _index(self, i: Any) -> int:
        if i.__class__ is not int:
            if isinstance(i, int) and not isinstance(i, bool):
                i = int(i)
            else:
                raise PlcTypeError(f"{self._path}[{i!r}]: an array index must be an integer")
        k = i - self._lo
        if k < 0 or k >= len(self._items):
            raise IndexError(f"{self._path}[{i}] is outside the array bounds {self._type.lo}..{self._type.hi}")
        return k

    def __getitem__(self, i: int) -> Any:
        return self._items[self._index(i)]

    def __setitem__(self, i: int, value: Any) -> None:
        k = self._index(i)
        if self._coerce is not None:
            self._items[k] = self._coerce(value, f"{self._path}[{i}]")
        else:
            copy_value(self._items[k], value, f"{self._path}[{i}]")

    def __len__(self) -> int:
        return len(self._items)

    def __iter__(self) -> Iterator[Any]:
        return iter(self._items)

    def __repr__(self) -> str:
        return f"<{self._path}: {self._items!r}>"


def copy_value(target: Any, value: Any, where: str) -> None:
    """Copy a struct or array value member by member (MOVE of a UDT), never by reference."""
    if isinstance(target, PlcStruct):
        if not isinstance(value, PlcStruct) or value._type is not target._type:
            vtype = value._type.name if isinstance(value, PlcStruct) else type(value).__name__
            raise PlcTypeError(f"{where} is {target._type.name}; cannot store a {vtype} (the types must match)")
        for key in target._type.members:
            store(target, key, value.__dict__[key])
        return
    if isinstance(target, PlcArray):
        if not isinstance(value, PlcArray) or value._type.name != target._type.name:
            raise PlcTypeError(f"{where} is {target._type.name}; cannot store {value!r} (the types must match)")
        for i in range(target._type.lo, target._type.hi + 1):
            target[i] = value[i]
        return
    raise PlcTypeError(f"{where} is a function-block instance; it cannot be assigned")


def store(obj: PlcStruct, key: str, value: Any) -> None:
    """Write ``value`` into member ``key`` of ``obj``, converted to the member's type.

    This is the one write path for stores the program compiler cannot type statically, HMI and
    scenario writes, and tags whose memory overlaps another tag.
    """
    member = obj._type.members.get(key)
    if member is None:
        raise UnknownTagError(_unknown(obj, key))
    mtype = member.type
    coerce = getattr(mtype, "coerce", None)
    if coerce is None:
        copy_value(obj.__dict__[key], value, f"{obj._path}.{key}" if obj._path != "t" else key)
        return
    value = coerce(value, key if obj._path == "t" else f"{obj._path}.{key}")
    cell = obj._aliased.get(key)
    if cell is None:
        obj.__dict__[key] = value
    else:
        cell.write(value)


# --------------------------------------------------------------------------------------------
# Building the live objects, start values, retain
# --------------------------------------------------------------------------------------------


def instantiate(member: Member, path: str, context: Any = None) -> Any:
    """Create the live value of a member: a scalar start value, a struct, an array or an FB instance."""
    mtype = member.type
    if isinstance(mtype, (ElementaryType, StringType)):
        return member.start_value() if isinstance(mtype, ElementaryType) else (member.start or "")
    if isinstance(mtype, StructType):
        obj = PlcStruct(mtype, path)
        start = member.start
        if isinstance(start, str) and mtype.name == "DTL":
            start = dtl_fields(start)
        for key, sub in mtype.members.items():
            if isinstance(start, Mapping) and key in start:
                sub = Member(sub.type, start[key], sub.retain, sub.comment)
            obj.__dict__[sys.intern(key)] = instantiate(sub, f"{path}.{key}", context)  # (as build_runtime's)
        return obj
    if isinstance(mtype, ArrayType):
        element = Member(mtype.element, mtype.element_start)
        starts = member.start if isinstance(member.start, list | tuple) else None
        items = []
        for k, i in enumerate(range(mtype.lo, mtype.hi + 1)):
            el = element if starts is None or k >= len(starts) else Member(mtype.element, starts[k])
            items.append(instantiate(el, f"{path}[{i}]", context))
        return PlcArray(mtype, path, items)
    if isinstance(mtype, FBType):
        return mtype.factory(context, member.start, path)
    raise DeclarationError(f"{path}: cannot create a value of type {mtype!r}")


def reset_to_start(obj: PlcStruct, *, keep_retain: bool = True) -> None:
    """Give every non-retain member its start value (STOP->RUN); retain members keep theirs."""
    for key, member in obj._type.members.items():
        _reset_member(obj, key, member, keep_retain, False)


def _reset_member(obj: Any, key: Any, member: Member, keep_retain: bool, inherited: bool) -> None:
    retain = member.retain or inherited
    mtype = member.type
    current = obj.__dict__[key] if isinstance(obj, PlcStruct) else obj._items[key]
    if isinstance(mtype, FBType):
        if not (keep_retain and retain):
            current.reset()
        return
    if isinstance(mtype, StructType):
        start = member.start
        if isinstance(start, str) and mtype.name == "DTL":
            start = dtl_fields(start)
        for sub_key, sub in mtype.members.items():
            if isinstance(start, Mapping) and sub_key in start:
                sub = Member(sub.type, start[sub_key], sub.retain, sub.comment)
            _reset_member(current, sub_key, sub, keep_retain, retain)
        return
    if isinstance(mtype, ArrayType):
        element = Member(mtype.element, mtype.element_start)
        starts = member.start if isinstance(member.start, list | tuple) else None
        for k in range(len(current._items)):
            el = element if starts is None or k >= len(starts) else Member(mtype.element, starts[k])
            _reset_member(current, k, el, keep_retain, retain)
        return
    if keep_retain and retain:
        return
    value = member.start_value() if isinstance(mtype, ElementaryType) else (member.start or "")
    if isinstance(obj, PlcArray):
        obj._items[key] = value
    else:
        cell = obj._aliased.get(key)
        if cell is None:
            obj.__dict__[key] = value
        else:
            cell.write(value)
