"""Host access to a running CPU: read and write tags as a watch table or an HMI does, force, peek at
absolute addresses. The watch-table half of :class:`plcsim.controllers.s7.cpu.CPU`."""

from __future__ import annotations

from typing import Any

from plcsim.controllers.s7.instructions import block_of
from plcsim.core.errors import PlcTypeError, UnknownTagError, did_you_mean
from plcsim.tags.memory import Address, parse_address
from plcsim.tags.types import ElementaryType
from plcsim.tags.values import PlcArray, PlcStruct, store


class HostAccess:
    """Watch table, HMI and force (a mixin: the state lives in :class:`plcsim.controllers.s7.cpu.CPU`)."""

    # -- host access: watch table, HMI, force ---------------------------------------------------

    def resolve_path(self, path: str) -> tuple[Any, Any]:
        """Find where ``"NAME"``, ``"DB.member"``, ``"DB.arr[2].x"`` or ``"%MW10"`` lives: (container, key)."""
        if not isinstance(path, str) or not path:
            raise UnknownTagError(f"a tag is named by a string such as 'LED' or 'DATA.D1_OBS', not {path!r}")
        text = path.strip()
        if text.startswith("%"):
            key = str(parse_address(text))
            if key in self.t.__dict__:
                return self.t, key
            entry = self.table.by_address(parse_address(text))
            if entry is not None:
                return self.t, entry.name
            raise UnknownTagError(f"no tag at {key}; declare it (Tag({key!r}, ...)) or use it in the program")
        parts = _split_path(text)
        container: Any = self.t
        for i, part in enumerate(parts[:-1]):
            container = _step(container, part, ".".join(str(p) for p in parts[: i + 1]))
        last = parts[-1]
        if isinstance(container, PlcArray):
            if not isinstance(last, int):
                raise UnknownTagError(f"{path}: an array needs an index, e.g. {text}[0]")
            container._index(last)
            return container, last
        block = block_of(container)
        if block is not None:  # a member the description names (hasattr would refresh a timer)
            if not isinstance(last, str) or block.member(last) is None:
                raise UnknownTagError(f"{path}: an instance of {type(container).__name__} has no member {last!r}")
            return container, last
        if not isinstance(container, PlcStruct):
            raise UnknownTagError(f"{path}: {parts[-2]} has no members")
        if last not in container._type.members:
            where = "no tag" if container is self.t else f"{container._path} has no member"
            raise UnknownTagError(f"{where} {last!r}{did_you_mean(str(last), container._type.members)}")
        return container, last

    def _resolve_value(self, path: str) -> Any:
        container, key = self.resolve_path(path)
        if block_of(container) is not None:
            return getattr(container, key)
        return container[key]

    def read(self, name: str) -> Any:
        """Read a tag, DB member, instance member (``"TON_1.ET"``, ``"C1.CV"``) or address as a watch table
        shows it (never refreshes a timer)."""
        text = name.strip()
        if text.startswith("%"):
            return self.peek(text)
        head, _, member = text.rpartition(".")
        owner = self._resolve_value(head) if head and "[" not in member else None
        block = block_of(owner)
        if block is not None:  # "TON_1.ET", "C1.CV": instance members, as last computed
            if block.member(member) is None:
                raise UnknownTagError(f"{head} has no member {member!r}")
            return getattr(owner, owner.trace_source(member))
        return self._resolve_value(text)

    def peek(self, address: str | Address) -> Any:
        """Read an absolute address from memory, composing it from every tag that overlaps it."""
        addr = parse_address(address) if isinstance(address, str) else address
        key = (addr.area, addr.db)
        memory = self.memories.get(key)
        if memory is None:
            raise UnknownTagError(f"{addr}: no such memory area (is the DB non-optimized?)")
        for container, name, caddr, dtype in self._cells:
            if caddr.area == addr.area and caddr.db == addr.db and caddr.byte < addr.end and addr.byte < caddr.end:
                memory.write(caddr, dtype, container.__dict__[name])
        return memory.read(addr, addr.default_type())

    def write(self, name: str, value: Any) -> None:
        """Modify a tag once, as a watch table or an HMI does; the program may overwrite it next scan."""
        container, key = self.resolve_path(name)
        if isinstance(container, PlcArray):
            container[key] = value
        elif block_of(container) is not None:
            store_instance_member(container, key, value)
        else:
            store(container, key, value)
        if key in self.inputs and container is self.t:
            self.inputs[key] = self.t.__dict__[key]
            self._sync_terminals(key)

    def set_input(self, name: str, value: Any) -> None:
        """Drive a physical input terminal (a sensor or a button); the program sees it at its next task start."""
        if name not in self.inputs:
            raise UnknownTagError(
                f"no input {name!r}{did_you_mean(name, self.inputs)}; inputs: {', '.join(self.inputs) or 'none'}"
            )
        member = self.table[name].member
        self.inputs[name] = member.type.coerce(value, name)  # type: ignore[union-attr]
        self._sync_terminals(name)

    def _sync_terminals(self, name: str) -> None:
        """After input ``name`` changed, give every input tag that overlaps it the same terminals."""
        cell = self._input_cells.get(name)
        if cell is not None:
            self._terminals.write(cell.address, cell.dtype, self.inputs[name])
            for other in cell.others:
                if other.key in self._input_cells:
                    self.inputs[other.key] = self._terminals.read(other.address, other.dtype)

    def force(self, name: str, value: Any) -> None:
        """Force a tag: its value is re-applied at every image update, whatever the program writes."""
        container, key = self.resolve_path(name)
        member_type = container._type.members[key].type if isinstance(container, PlcStruct) else None
        if isinstance(member_type, ElementaryType):
            value = member_type.coerce(value, name)
        self.forces[name] = value
        self._diag("force", f"{name} forced to {value!r}")

    def unforce(self, name: str | None = None) -> None:
        """Remove one force (or all): the tag keeps the forced value until something writes it."""
        names = list(self.forces) if name is None else [name]
        for n in names:
            if n not in self.forces:
                raise UnknownTagError(f"{n!r} is not forced; forced: {', '.join(self.forces) or 'nothing'}")
            del self.forces[n]


def store_into(container: Any, key: str, value: Any) -> None:
    if isinstance(container, PlcStruct):
        store(container, key, value)
        return
    raise PlcTypeError(
        f"cannot store into {type(container).__name__}.{key}; a program stores only into tags "
        f"(t.NAME) and data-block members (t.DB.member)"
    )


def store_instance_member(instance: Any, key: str, value: Any) -> None:
    """Write a writable member of an instance (a timer's PT, a counter's CV or PV), converted."""
    block = block_of(instance)
    if block is None or key not in block.writable:
        raise PlcTypeError(f"{key} of {instance!r} cannot be written by the program")
    instance.write_member(key, value)


def _split_path(text: str) -> list[Any]:
    parts: list[Any] = []
    for chunk in text.split("."):
        name, _, rest = chunk.partition("[")
        if name:
            parts.append(name)
        while rest:
            index, _, rest = rest.partition("]")
            try:
                parts.append(int(index))
            except ValueError:
                raise UnknownTagError(f"{text!r}: array index {index!r} must be an integer") from None
            rest = rest.lstrip("[")
    return parts


def _step(container: Any, part: Any, shown: str) -> Any:
    if isinstance(part, int):
        if not isinstance(container, PlcArray):
            raise UnknownTagError(f"{shown} is not an array")
        return container[part]
    if isinstance(container, PlcStruct):
        if part not in container.__dict__:
            where = "no tag" if container._path == "t" else f"{container._path} has no member"
            raise UnknownTagError(f"{where} {part!r}{did_you_mean(part, container._type.members)}")
        return container.__dict__[part]
    raise UnknownTagError(f"{shown}: {type(container).__name__} has no member {part!r}")
