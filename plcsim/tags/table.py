"""Tag table and data blocks: declarations, and the live objects a program reads and writes.

A program sees one object, ``t``, whose attributes are the tags: ``t.S1`` is a BOOL input,
``t.DATA.D1_POZ1_OBS`` a member of the global DB ``DATA``, ``t.TON_A`` a timer instance. Reading a
tag is a plain attribute read; every store is converted to the tag's S7 type (see
:mod:`plcsim.tags.types`). Tags whose addresses overlap (``%MW10`` and ``%M11.0``) are kept consistent
through byte memory, as on the CPU.

>>> table = TagTable()
>>> _ = table.add("CISLO", Tag("%MW10", Int))
>>> _ = table.add("LOW_BIT", Tag("%M11.0"))
>>> t = build_tags(table)
>>> store(t, "CISLO", 3)
>>> t.LOW_BIT
True
"""

from __future__ import annotations

from collections.abc import Callable, Iterator, Mapping
from dataclasses import dataclass, field
from typing import Any

from plcsim.core.errors import AddressError, DeclarationError, PlcTypeError, UnknownTagError, did_you_mean
from plcsim.tags.memory import Address, ByteMemory, parse_address
from plcsim.tags.types import (
    ArrayType,
    Bool,
    DataType,
    ElementaryType,
    Int,
    Member,
    StringType,
    StructType,
    as_member,
    dtl_fields,
)

__all__ = ["Bool", "Int"]  # re-exported for the doctest above; the public names live in plcsim


# --------------------------------------------------------------------------------------------
# Declarations
# --------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class Tag:
    """A PLC tag bound to an absolute address: ``Tag("%I0.0")``, ``Tag("%MW12", Int)``.

    The type defaults to BOOL for a bit address; a byte/word/dword address needs its type.
    """

    address: str
    type: DataType | None = None
    retain: bool = False
    start: Any = None
    comment: str = ""

    def resolved(self) -> tuple[Address, ElementaryType]:
        """Parse the address and check that the type fits its width."""
        addr = parse_address(self.address)
        dtype = self.type
        if dtype is None:
            if addr.bits != 1:
                raise DeclarationError(
                    f"tag at {addr}: give its type, e.g. Tag({self.address!r}, Int); only bit addresses default to Bool"
                )
            dtype = Bool
        if not isinstance(dtype, ElementaryType):
            raise DeclarationError(f"tag at {addr}: a PLC tag must have an elementary type, not {dtype!r}")
        if dtype.bits != addr.bits:
            width = {1: "a bit", 8: "a byte (B)", 16: "a word (W)", 32: "a double word (D)", 64: "an L"}
            raise DeclarationError(
                f"tag at {addr}: {dtype.name} has {dtype.bits} bits but the address is {width[addr.bits]} address; "
                f"use {_suggest_address(addr, dtype)}"
            )
        return addr, dtype


def _suggest_address(addr: Address, dtype: ElementaryType) -> str:
    letter = {1: "", 8: "B", 16: "W", 32: "D", 64: "L"}[dtype.bits]
    if dtype.bits == 1:
        return f"%{addr.area}{addr.byte}.0"
    return f"%{addr.area}{letter}{addr.byte}"


@dataclass(frozen=True)
class DataBlock:
    """A global data block: ``DB(number=1, D1_OBS=Bool, POCET=Int(0, retain=True))``.

    Attributes:
        members: member name -> :class:`Member`.
        number: the DB number (automatic when None).
        optimized: symbolic access only (TIA default); a non-optimized DB also has absolute
            addresses ``%DBn.DBXb.c`` laid out as classic S7 does.
        retain: default retain flag for members declared without one.
    """

    members: Mapping[str, Member]
    number: int | None = None
    optimized: bool = True
    retain: bool = False
    comment: str = ""

    def struct_type(self, name: str) -> StructType:
        """The DB as a struct type."""
        members = {}
        for key, member in self.members.items():
            if self.retain and not member.retain:
                member = Member(member.type, member.start, True, member.comment)
            members[key] = member
        return StructType(name, members)


def DB(
    *,
    number: int | None = None,
    optimized: bool = True,
    retain: bool = False,
    comment: str = "",
    **members: DataType | Member,
) -> DataBlock:
    """Declare a global data block with its members (keyword per member)."""
    return DataBlock({k: as_member(v, k) for k, v in members.items()}, number, optimized, retain, comment)


class FBType(DataType):
    """The type of a function-block instance (IEC_TIMER, IEC_COUNTER, R_TRIG, F_TRIG).

    Calling the type declares an instance: ``TON_A = IEC_TIMER()``, ``C1 = IEC_COUNTER(DInt)``.
    """

    bits = 0

    def __init__(self, name: str, factory: Callable[..., Any], retain: bool, doc: str = ""):
        self.name, self.factory, self.retain_default = name, factory, retain
        self.__doc__ = doc

    def __call__(
        self,
        value_type: DataType | None = None,
        *,
        retain: bool | None = None,  # type: ignore[override]
        comment: str = "",
    ) -> Member:
        start = value_type
        return Member(self, start, self.retain_default if retain is None else retain, comment)

    def default(self) -> Any:
        return None


# --------------------------------------------------------------------------------------------
# Tag table
# --------------------------------------------------------------------------------------------


@dataclass
class TagEntry:
    """One declared name: a PLC tag (with address), a symbol, a data block or an FB instance."""

    name: str
    member: Member
    address: Address | None = None
    db: DataBlock | None = None
    source: str = ""


@dataclass
class TagTable:
    """The declared names of one CPU: PLC tags, symbols, data blocks and instances.

    The exercise declares its I/O table here; a program adds its own names.
    """

    entries: dict[str, TagEntry] = field(default_factory=dict)

    def add(self, name: str, decl: Tag | DataBlock | Member | DataType, *, source: str = "") -> TagEntry:
        """Declare ``name``; raises DeclarationError if the name is taken."""
        if not isinstance(name, str) or not name:
            raise DeclarationError(f"a tag name must be a non-empty string, not {name!r}")
        if name in self.entries:
            prev = self.entries[name]
            raise DeclarationError(
                f"{source or 'declaration'}: {name!r} is already declared"
                f"{' by ' + prev.source if prev.source else ''}; choose another name"
            )
        if isinstance(decl, Tag):
            addr, dtype = decl.resolved()
            entry = TagEntry(name, Member(dtype, decl.start, decl.retain, decl.comment), addr, source=source)
        elif isinstance(decl, DataBlock):
            entry = TagEntry(name, Member(decl.struct_type(name), None, False, decl.comment), db=decl, source=source)
        elif isinstance(decl, (Member, DataType)):
            entry = TagEntry(name, as_member(decl, name), source=source)
        else:
            raise DeclarationError(
                f"{source or name}: {name} = {decl!r} is not a declaration; use Tag('%M10.0'), Int(0), "
                f"DB(...), IEC_TIMER() ..."
            )
        self.entries[name] = entry
        return entry

    def __contains__(self, name: object) -> bool:
        return name in self.entries

    def __iter__(self) -> Iterator[TagEntry]:
        return iter(self.entries.values())

    def __getitem__(self, name: str) -> TagEntry:
        try:
            return self.entries[name]
        except KeyError:
            raise UnknownTagError(f"no tag {name!r}{did_you_mean(name, self.entries)}") from None

    def by_address(self, address: Address) -> TagEntry | None:
        """The tag declared at exactly this address, if any."""
        for entry in self.entries.values():
            if entry.address == address:
                return entry
        return None

    def copy(self) -> TagTable:
        """A shallow copy to which a program can add its own names."""
        return TagTable(dict(self.entries))

    def schema(self) -> StructType:
        """The root struct type of ``t``: one member per name."""
        root = StructType("tags", {})
        root.members = {name: e.member for name, e in self.entries.items()}
        return root

    def db_numbers(self) -> dict[str, int]:
        """Assign DB numbers: declared ones first, then the first unused numbers (TIA's automatic)."""
        numbers: dict[str, int] = {}
        used: dict[int, str] = {}
        for name, entry in self.entries.items():
            if entry.db is not None and entry.db.number is not None:
                if entry.db.number in used:
                    raise DeclarationError(
                        f"DB number {entry.db.number} is used by both {used[entry.db.number]!r} and {name!r}"
                    )
                used[entry.db.number] = name
                numbers[name] = entry.db.number
        free = 1
        for name, entry in self.entries.items():
            if entry.db is not None and entry.db.number is None:
                while free in used:
                    free += 1
                used[free] = name
                numbers[name] = free
        return numbers


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
            obj.__dict__[key] = instantiate(sub, f"{path}.{key}", context)
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
        t.__dict__[name] = value
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
