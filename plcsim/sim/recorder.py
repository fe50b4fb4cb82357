"""What the trace records from a controller, and the fast per-scan row getter.

By default: every input, output and memory tag, every scalar member of a data block, each timer's
Q and ET, each counter's CV, QU and QD. Clock and system memory bits are left out unless the
program uses them. Reading for the trace never refreshes a timer (observing changes nothing).

An input is recorded as the plant and the wiring delivered it: the value its last refresh of the
process image read (OB1's at the start of the scan, or an interrupt's that read it since), before any
network ran. A program that writes an input tag changes what it reads itself, never what the trace
(and so the grader) sees.
"""

from __future__ import annotations

import re
from collections import Counter
from collections.abc import Callable, Sequence
from typing import Any

from plcsim.controllers.protocol import Controller
from plcsim.controllers.s7.instructions import block_of
from plcsim.core.errors import UnknownTagError, did_you_mean
from plcsim.core.observers import Subscribers
from plcsim.tags.types import ElementaryType
from plcsim.tags.values import PlcStruct
from plcsim.trace.facade import BLOCK, Trace
from plcsim.trace.rows import UNPACKABLE


def _type_name(dtype: Any) -> str:
    if isinstance(dtype, ElementaryType):
        return {"bool": "bool", "real": "real"}.get(dtype.kind, "int")
    return "int"


def default_signals(cpu: Controller) -> list[str]:
    """The signals traced when none are chosen."""
    used: set[str] = set()
    if cpu.loaded is not None:
        used = set(cpu.loaded.facts.tags_read | cpu.loaded.facts.tags_written)
    names: list[str] = []
    for entry in cpu.table:
        value = cpu.t.__dict__[entry.name]
        if entry.name.startswith("%"):
            continue
        if entry.name in cpu.system_tags and entry.name not in used:
            continue
        block = block_of(value)
        if isinstance(entry.member.type, ElementaryType):
            names.append(entry.name)
        elif block is not None:
            names += [f"{entry.name}.{member}" for member in block.traced]
        elif isinstance(value, PlcStruct):
            names += _struct_members(value, entry.name)
    return names


def _struct_members(value: PlcStruct, path: str, depth: int = 2) -> list[str]:
    """Scalar members of a DB, and of the structs in it (a DTL), as dotted names."""
    names = []
    for key, member in value._type.members.items():
        if isinstance(member.type, ElementaryType):
            names.append(f"{path}.{key}")
        elif depth > 1 and isinstance(value.__dict__[key], PlcStruct):
            names += _struct_members(value.__dict__[key], f"{path}.{key}", depth - 1)
    return names


class Recorder:
    """Writes one trace row per OB1 scan (and per interrupt execution) from a controller.

    Args:
        cpu: the CPU to observe.
        signals: names to record (``"S1"``, ``"DATA.D1_OBS"``, ``"TON_A.ET"``); default: :func:`default_signals`.
        changes_only: write a row only when a value changed (for hours-long runs).
        observed: ``(names, sample)``: analog values of the plant recorded after the tags in every row (kind
            ``analog``, type ``real``); ``sample()`` returns them in that order, as the plant is when the row is
            written (a press's ram height: see ``TRACED_OBSERVABLES`` in :mod:`plcsim.plant.protocol`).
    """

    def __init__(
        self,
        cpu: Controller,
        signals: Sequence[str] | None = None,
        *,
        changes_only: bool = False,
        observed: tuple[Sequence[str], Callable[[], tuple[float, ...]]] | None = None,
    ):
        self.cpu = cpu
        names = list(signals) if signals is not None else default_signals(cpu)
        kinds, types, sources = {}, {}, []
        for name in names:
            kind, dtype, source = self._locate(name)
            kinds[name], types[name] = kind, dtype
            sources.append(source)
        extra, sample = (list(observed[0]), observed[1]) if observed else ([], None)
        for name in extra:
            if name in kinds:
                raise UnknownTagError(f"cannot trace the plant's {name!r}: a traced tag has that name")
            kinds[name], types[name] = "analog", "real"
        self.trace = Trace(names + extra, kinds, types)
        self.row = _compile_getter(sources, sample=sample)
        physical = [f"o[{n!r}]" if kinds[n] == "output" else src for n, src in zip(names, sources)]
        self._stopped_row = _compile_getter(physical, outputs=True, sample=sample)
        self.changes_only = changes_only
        self._last: tuple[Any, ...] | None = None
        self._subscriptions: list[tuple[Subscribers, Callable[..., None]]] = []
        self._sources, self._sample, self._sampled = sources, sample, len(extra)
        self.packed_row = _compile_getter(sources, sample=sample, into=(self.trace.row_sink().pack_values, len(extra)))
        """:attr:`row` packed for the trace's rows (raises one of :data:`~plcsim.trace.rows.UNPACKABLE` for a value its
        column cannot hold): what every-row recording writes."""
        self._tags: dict[str, Any] = cpu.t.__dict__
        """The tags the rows of :attr:`scan_hook` read: the CPU's when :meth:`attach` was called."""
        self._regular: tuple[tuple[int, int], Callable[[int, int], None]] | None = None
        """The last :meth:`regular_row` with its step and task."""
        self.scan_hook: Callable[[Controller], None] | None = None
        """What :meth:`attach` subscribed to the CPU's scan end (None while detached)."""

    def _locate(self, name: str) -> tuple[str, str, str]:
        cpu = self.cpu
        head, _, rest = name.partition(".")
        if head not in cpu.t.__dict__:
            raise UnknownTagError(f"cannot trace {name!r}: no tag {head!r}{did_you_mean(head, cpu.t.__dict__)}")
        value = cpu.t.__dict__[head]
        entry = cpu.table[head]
        if not rest:
            if not isinstance(entry.member.type, ElementaryType):
                raise UnknownTagError(f"cannot trace {name!r}: it is a {entry.member.type.name}; trace its members")
            area = entry.address.area if entry.address is not None else "M"
            kind = {"I": "input", "Q": "output"}.get(area, "memory")
            return kind, _type_name(entry.member.type), f"{'i' if kind == 'input' else 'd'}[{head!r}]"
        block = block_of(value)
        if block is not None:
            if block.member(rest) is None:
                members = ", ".join(block.readable)
                raise UnknownTagError(f"cannot trace {name!r}: an instance of {block.name} has {members}")
            return block.trace_kind, block.trace_type(rest), f"d[{head!r}].{value.trace_source(rest)}"
        container, key = cpu.resolve_path(name)
        if not isinstance(container, PlcStruct):
            raise UnknownTagError(f"cannot trace {name!r}: array elements are not traced; copy it to a tag")
        mtype = container._type.members[key].type
        if not isinstance(mtype, ElementaryType):
            raise UnknownTagError(f"cannot trace {name!r}: it is a {mtype.name}; trace its members")
        path = "d" + "".join(f"[{p!r}]" if i == 0 else f".__dict__[{p!r}]" for i, p in enumerate(name.split(".")))
        return "db", _type_name(mtype), path

    # -- hooks ---------------------------------------------------------------------------------

    def attach(self) -> None:
        """Start recording: every OB1 scan, every interrupt execution and every execution a power cut
        interrupts writes a row."""
        cpu = self.cpu
        self._tags = cpu.t.__dict__
        self._regular = None
        self.scan_hook = self.on_scan if self.changes_only else self._fast_on_scan()
        self._subscriptions = [
            (cpu.scan_end, self.scan_hook),
            (cpu.task_end, self.on_task),
            (cpu.cut, self.on_cut),
        ]
        for hook, subscriber in self._subscriptions:
            hook.add(subscriber)
        self.trace.task_numbers.update(cpu.task_numbers)

    def detach(self) -> None:
        """Stop recording (the other subscribers of the CPU's hooks stay)."""
        for hook, subscriber in self._subscriptions:
            hook.remove(subscriber)
        self._subscriptions = []
        self.scan_hook = None

    def on_scan(self, cpu: Controller) -> None:
        values = self.row(cpu.t.__dict__, cpu.image_in)
        if self.changes_only:
            if values == self._last:
                return
            self._last = values
        self.trace.add_row(cpu.scan_start_ns, cpu.scan_end_ns, cpu.scan_task_number, values)

    def _fast_on_scan(self) -> Callable[[Controller], None]:
        """:meth:`on_scan` for every-row recording, with :meth:`~plcsim.trace.rows.RunLengthRows.add` written out:
        the hot path of a run."""
        rows = self.trace.row_sink()
        heads, values_at, changes, last, pack = rows.heads, rows.values, rows.changes, rows.last, rows.pack
        packed_row = self.packed_row
        pack_head, row, add, d = rows.pack_head, self.row, rows.add, self._tags

        def on_scan(cpu: Controller) -> None:
            try:
                values = packed_row(d, cpu.image_in)
                heads.append(pack_head(cpu.scan_start_ns, cpu.scan_end_ns, cpu.scan_task_number))
            except UNPACKABLE:  # a value its column cannot hold: the general path keeps the row as it is
                add(cpu.scan_start_ns, cpu.scan_end_ns, cpu.scan_task_number, row(d, cpu.image_in))
                return
            if values != last[0]:
                last[0] = values
                changes.append(len(heads) - 1)
                values_at.append(values)
            if len(heads) >= BLOCK:
                pack()

        return on_scan

    def regular_row(self, duration_ns: int, task: int) -> Callable[[int, int], None]:
        """:attr:`scan_hook` as ``row(start, end)`` for scans that all last ``duration_ns`` and belong to ``task``
        (a co-simulation's fused step, :mod:`plcsim.sim.stepping`): each row's head is its start time alone (a
        regular row of :class:`~plcsim.trace.rows.RunLengthRows`), so no head is packed; its values are packed
        in the same generated function (:attr:`packed_row`'s code), one call per row instead of two."""
        rows = self.trace.row_sink()
        rows.set_regular(duration_ns, task)
        if self._regular is not None and self._regular[0] == (duration_ns, task):
            return self._regular[1]  # (generated once per attachment and step: a run builds its step again often)
        store = {"cpu": self.cpu, "d": self._tags, "task": task, "general": self.row, "UNPACKABLE": UNPACKABLE}
        store.update(heads=rows.heads, values_at=rows.values, changes=rows.changes, last=rows.last, add=rows.add)
        store.update(pack=rows.pack, BLOCK=BLOCK, len=len)
        into = (rows.pack_values, self._sampled)
        regular = _compile_getter(self._sources, sample=self._sample, into=into, store=store)
        self._regular = ((duration_ns, task), regular)
        return regular

    def on_task(self, cpu: Controller, task: str, start_ns: int, end_ns: int) -> None:
        values = self.row(cpu.t.__dict__, cpu.image_in)
        if self.changes_only:
            if values == self._last:
                return
            self._last = values
        self.trace.add_row(start_ns, end_ns, self._number(task), values)

    def on_cut(self, cpu: Controller, task: str, start_ns: int) -> None:
        """The row of an execution a power cut interrupted: what its networks did is kept (retentive
        tags keep it through the restart, so a check must see it); it ends at the cut, and its outputs
        are what the modules drive from then on (off)."""
        values = self._stopped_row(cpu.t.__dict__, cpu.image_in, cpu.outputs)
        if self.changes_only and values == self._last:
            return
        self._last = values
        self.trace.add_row(start_ns, cpu.now, self._number(task), values)

    def _number(self, task: str) -> int:
        """The task column of ``task``, as the CPU's loaded program numbers it (kept with the trace)."""
        number = self.cpu.task_numbers[task]
        self.trace.task_numbers.setdefault(task, number)
        return number

    def on_stopped(self, t_ns: int, end_ns: int) -> None:
        """A row while the CPU is in STOP: no scan runs; the outputs are what the modules drive (off)."""
        values = self._stopped_row(self.cpu.t.__dict__, self.cpu.image_in, self.cpu.outputs)
        if self.changes_only and values == self._last:
            return
        self._last = values
        self.trace.add_row(t_ns, end_ns, 0, values)


def _compile_getter(
    sources: list[str],
    outputs: bool = False,
    sample: Callable[[], tuple[float, ...]] | None = None,
    into: tuple[Callable[..., Any], int] | None = None,
    store: dict[str, Any] | None = None,
) -> Callable[..., Any]:
    """A function returning the row as a tuple, generated once from the access paths (our code, not a
    program's): ``d`` is the CPU's tags, ``i`` the inputs as delivered (:attr:`CPU.image_in`). With ``outputs``
    it takes the output modules' values ``o`` (the sources name them); ``sample()``'s values end the row.
    With ``into`` (a function and how many values ``sample()`` returns) it returns ``function(*row)`` instead
    (the row packed: :mod:`plcsim.trace.rows`), ``sample()`` unpacked into names (a call with ``*`` costs more).
    With ``store`` too (the names :data:`_STORE` uses), it is ``regular(start, end)`` that stores the packed row
    as :meth:`Recorder.regular_row` says, reading ``cpu.image_in`` and the tags ``d``.

    >>> row = _compile_getter(["i['S1']", "d['M']"], sample=lambda: (1.5, 2.5), into=(lambda *v: v, 2))
    >>> row({"M": 7}, {"S1": True})
    (True, 7, 1.5, 2.5)
    >>> _compile_getter([], sample=lambda: (1.5, 2.5))({}, {})
    (1.5, 2.5)
    >>> _compile_getter([], sample=lambda: (1.5,), into=(lambda *v: v, 2))({}, {})
    Traceback (most recent call last):
    ValueError: not enough values to unpack (expected 2, got 1)
    """
    bases, sources = _shared_bases(sources)
    scope: dict[str, Any] = {"__builtins__": {}, "s": sample}
    args = "d, i, o" if outputs else "d, i"
    lines = [f"    {name} = {base}\n" for base, name in bases.items()]
    body = "".join(f"{source}, " for source in sources)
    if into is None:
        row = f"({body}{'*s(), ' if sample is not None else ''})"  # a tuple even when ``s()`` is all of it
    else:
        scope["p"], sampled = into
        names = [f"_s{k}" for k in range(sampled if sample is not None else 0)]
        if names:  # a sample of another length raises ValueError: the row then takes the general path
            lines.append(f"    {''.join(f'{name}, ' for name in names)}= s()\n")
        row = f"p({body}{''.join(f'{name}, ' for name in names)})"
    if store is not None:  # the same lines inside the writer's try (what raises there takes the general path)
        scope.update(store)
        inner = "".join(f"    {line}" for line in lines)
        exec(
            f"def regular(start, end):\n    i = cpu.image_in\n    try:\n{inner}        values = {row}\n{_STORE}", scope
        )
        return scope["regular"]
    exec(f"def row({args}):\n{''.join(lines)}    return {row}\n", scope)  # built from tag names, not program text
    return scope["row"]


_STORE = """\
    except UNPACKABLE:
        add(start, end, task, general(d, i))
        return
    heads.append(start)
    if values != last[0]:
        last[0] = values
        changes.append(len(heads) - 1)
        values_at.append(values)
    if len(heads) >= BLOCK:
        pack()
"""
"""The end of a generated regular row (:meth:`Recorder.regular_row`): a row its columns cannot hold is added
as it is (a tuple), else its start alone is appended, its values only when they changed (``RunLengthRows.add``
written out)."""


_BASE = re.compile(r"""(d\[(?:'[^'\\]*'|"[^"\\]*")\](?:\.__dict__)?)(\[.+|\..+)""")
"""A source read through a block or a data block: ``d['DB'].__dict__`` + ``['member']``, ``d['T1']`` + ``.ET``."""


def _shared_bases(sources: list[str]) -> tuple[dict[str, str], list[str]]:
    """The blocks that several sources read through, each looked up once per row into a local (a DB with
    nine traced members: one lookup instead of nine), and the sources rewritten to read the locals.

    >>> _shared_bases(["i['S1']", "d['DB'].__dict__['A']", "d['DB'].__dict__['B']", "d['T1'].Q"])
    ({"d['DB'].__dict__": '_b0'}, ["i['S1']", "_b0['A']", "_b0['B']", "d['T1'].Q"])
    """
    split = [_BASE.fullmatch(source) for source in sources]
    counts = Counter(m.group(1) for m in split if m)
    bases = {base: f"_b{k}" for k, base in enumerate(b for b, count in counts.items() if count > 1)}
    rewritten = [
        bases[m.group(1)] + m.group(2) if m and m.group(1) in bases else source for m, source in zip(split, sources)
    ]
    return bases, rewritten
