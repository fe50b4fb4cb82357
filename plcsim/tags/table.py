"""The tag table: the names a CPU declares (PLC tags at addresses, data blocks, FB instances).

Declarations only, no values: an exercise declares its I/O table here and a program adds its own names.
Both controllers read the same table; the S7 CPU makes its live values from it
(:mod:`plcsim.tags.values`, built into ``t`` by :mod:`plcsim.tags.runtime`).
"""

from __future__ import annotations

from collections.abc import Callable, Iterator, Mapping
from dataclasses import dataclass, field
from typing import Any

from plcsim.core.errors import DeclarationError, UnknownTagError, did_you_mean
from plcsim.tags.memory import Address, parse_address
from plcsim.tags.types import Bool, DataType, ElementaryType, Member, StructType, as_member

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

    The exercise declares its I/O table here; a program adds its own names. ``aliases`` are other names a
    program may use for a declared tag or data-block member (the textbook's table and prose spell some apart:
    ``Dopravník`` is ``D1_VPRED``); the front ends read an alias as the name it stands for.
    """

    entries: dict[str, TagEntry] = field(default_factory=dict)
    aliases: dict[str, str] = field(default_factory=dict)

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

    def add_alias(self, alias: str, name: str) -> None:
        """Let a program write ``alias`` for ``name`` (a tag, or ``DB.member``); an alias with spaces, which no
        program can write as ``t.X``, is also accepted with each space written ``_``.

        >>> table = TagTable()
        >>> _ = table.add("D1_VPRED", Tag("%Q0.0"))
        >>> table.add_alias("Piest1 Dopravník", "D1_VPRED")
        >>> sorted(table.aliases)
        ['Piest1 Dopravník', 'Piest1_Dopravník']
        """
        head, _, member = name.partition(".")
        entry = self.entries.get(head)
        members = getattr(entry.member.type, "members", {}) if entry is not None else {}
        if entry is None or (member and member not in members):
            raise UnknownTagError(f"alias {alias!r} stands for {name!r}, which is not declared")
        for spelling in dict.fromkeys((alias, alias.replace(" ", "_"))):
            if spelling.partition(".")[0] in self.entries and spelling != name and "." not in spelling:
                raise DeclarationError(f"alias {spelling!r} is already a declared name; choose another alias")
            self.aliases[spelling] = name

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
        return TagTable(dict(self.entries), dict(self.aliases))

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
