"""The run's record: one row per scan of I/O images and chosen tags, plant events, plant geometry.

This is the table alone; its exporters (:mod:`plcsim.trace.plot`, :mod:`plcsim.trace.rerun`) import it,
never the other way round, and :class:`plcsim.trace.facade.Trace` puts them on the table as methods.

Rows are appended as tuples (cheap on the hot path), their values only when they changed
(:mod:`plcsim.trace.rows`), and packed into numpy blocks of :data:`BLOCK` rows; queries see one float64
column per signal, a value in every row. Booleans are stored as 0.0/1.0.

An output is valid from the end of the scan that wrote it, an input from the start of the scan
that read it:

>>> tr = TraceTable(["S1", "D1"], kinds={"S1": "input", "D1": "output"}, types={"S1": "bool", "D1": "bool"})
>>> for k, (s1, d1) in enumerate([(0, 0), (1, 0), (1, 1), (0, 1), (0, 0)]):
...     tr.add_row(k * 1_000_000, (k + 1) * 1_000_000, 1, (bool(s1), bool(d1)))
>>> tr.rises("S1").tolist(), tr.rises("D1").tolist()
([1000000], [3000000])
>>> tr.intervals("D1")
[(3000000, 5000000)]
>>> tr.value_at("D1", 3_500_000)
True

**Row order.** A row is written when its execution ends, so rows are in the order of their end times
(ties in the order they were recorded), and each row holds the state at its end. An OB30 call that
pre-empts an OB1 scan ends, and is recorded, before that scan: start times are in order only within one
task. Ask per task rather than ``searchsorted`` over :attr:`TraceTable.times`: :meth:`TraceTable.of_task` (the rows
of one task), :meth:`TraceTable.scan_after` (the scan that saw something that happened at a time),
:meth:`TraceTable.value_at`. An input holds what the plant delivered at its last refresh (OB1's at the scan
start, or an interrupt's that read it since), never what the program wrote into it:

>>> tr = TraceTable(["S1"], kinds={"S1": "input"}, types={"S1": "bool"})
>>> tr.add_row(0, 10_000_000, 1, (False,))
>>> tr.add_row(12_000_000, 13_000_000, 30, (True,))  # OB30 at 12 ms read S1 TRUE, inside the scan from 10 ms
>>> tr.add_row(10_000_000, 21_000_000, 1, (True,))
>>> tr.add_row(21_000_000, 31_000_000, 1, (True,))
>>> tr.rises("S1").tolist(), tr.scan_after(11_000_000), tr.scan_after(11_000_000, task="OB30")
([12000000], 3, 1)
>>> tr.of_task("OB1").times.tolist(), tr.value_at("S1", 5_000_000), tr.value_at("S1", 12_000_000)
([0, 10000000, 21000000], False, True)
"""

from __future__ import annotations

import json
import re
from collections.abc import Iterable, Sequence
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from plcsim.core.errors import UnknownTagError, did_you_mean
from plcsim.plant.protocol import Drawable, PlantEvent
from plcsim.trace.rows import BLOCK, HEAD, RunLengthRows

__all__ = ["BLOCK", "HEAD", "GeometryFrame", "TraceEvent", "TraceTable"]


_HEAD_NAMES = ("start_ns", "end_ns", "task")
"""The row heads as :meth:`TraceTable.save` names them: each row's execution start and end and its task."""
_SAVED_DTYPES = {"bool": np.bool_, "int": np.int64}
"""How :meth:`TraceTable.save` stores a signal of each type (a Real, or a column of no type: float64)."""
_CODES = {"bool": "b", "int": "q"}
"""How a row packs a value of each type (:mod:`plcsim.trace.rows`; a Real, or a column of no type: a double)."""


@dataclass(frozen=True)
class TraceEvent:
    """An event of the run: a plant event, a scenario action, a CPU mode change or diagnostic."""

    t_ns: int
    source: str  # "plant", "scenario", "cpu", "wiring"
    kind: str
    subject: str = ""
    part: str | None = None
    detail: str = ""
    data: dict[str, float | int | str | bool] = field(default_factory=dict)  # a plant event's measurements

    def __str__(self) -> str:
        who = f" {self.subject}" if self.subject else ""
        part = f" ({self.part})" if self.part else ""
        detail = f": {self.detail}" if self.detail else ""
        return f"{self.t_ns / 1e9:10.3f} s  {self.source:8s} {self.kind}{who}{part}{detail}"


@dataclass
class GeometryFrame:
    """The plant's moving shapes at one instant."""

    t_ns: int
    drawables: list[Drawable]


@dataclass
class TraceTable:
    """Columns of a run plus its events and geometry (the table; :class:`plcsim.trace.facade.Trace` adds the
    exporters as methods).

    Attributes:
        names: the signal names, in column order.
        kinds: name -> ``input``, ``output``, ``memory``, ``db``, ``timer``, ``counter``, ``analog``.
        types: name -> ``bool``, ``int`` or ``real``.
    """

    names: list[str]
    kinds: dict[str, str] = field(default_factory=dict)
    types: dict[str, str] = field(default_factory=dict)
    meta: dict[str, Any] = field(default_factory=dict)
    events: list[TraceEvent] = field(default_factory=list)
    frames: list[GeometryFrame] = field(default_factory=list)
    static_drawables: list[Drawable] = field(default_factory=list)
    bounds: tuple[float, float, float, float] | None = None
    task_numbers: dict[str, int] = field(default_factory=dict)
    """Task name -> its number in the task column, as the recording CPU's tasks declared it."""

    def __post_init__(self) -> None:
        self._index = {name: i for i, name in enumerate(self.names)}
        self._rows = RunLengthRows("".join(_CODES.get(self.types.get(name), "d") for name in self.names))
        self._blocks: list[np.ndarray] = []
        self._packed: np.ndarray | None = None
        self._empty = np.zeros((0, HEAD + len(self.names)))

    # -- writing -------------------------------------------------------------------------------

    def add_row(self, t_ns: int, t_end_ns: int, task: int, values: Sequence[Any]) -> None:
        """Append one row: scan start, scan end, task number (1 = OB1), then the values in column order."""
        self._rows.add(t_ns, t_end_ns, task, tuple(values))

    def row_sink(self) -> RunLengthRows:
        """The rows being written (for a recorder that appends to them itself; see :mod:`plcsim.sim.recorder`)."""
        return self._rows

    def add_event(self, event: TraceEvent) -> None:
        """Record an event."""
        self.events.append(event)

    def add_plant_events(self, events: Iterable[PlantEvent]) -> None:
        """Record plant events."""
        for e in events:
            detail = ", ".join(f"{k}={_short(v)}" for k, v in e.data.items()) if e.data else ""
            data = {str(k): _scalar(v) for k, v in e.data.items()} if e.data else {}
            self.events.append(TraceEvent(e.t_ns, "plant", e.kind, e.subject, e.part, detail, data))

    def add_frame(self, t_ns: int, drawables: list[Drawable]) -> None:
        """Record the plant's moving shapes."""
        self.frames.append(GeometryFrame(t_ns, drawables))

    # -- reading -------------------------------------------------------------------------------

    @property
    def table(self) -> np.ndarray:
        """All rows as one (rows, 3 + signals) float64 array: t_ns, t_end_ns, task, then the values."""
        if len(self._rows):
            self._blocks.append(self._rows.take())
            self._packed = None
        if self._packed is None:
            self._packed = np.concatenate(self._blocks) if self._blocks else self._empty
            self._blocks = [self._packed] if len(self._packed) else []
        return self._packed

    def __len__(self) -> int:
        return sum(len(b) for b in self._blocks) + len(self._rows)

    @property
    def times(self) -> np.ndarray:
        """Row times (scan start, when the inputs were read) as int64 ns."""
        return self.table[:, 0].astype(np.int64)

    @property
    def end_times(self) -> np.ndarray:
        """Row end times (when the outputs were written) as int64 ns."""
        return self.table[:, 1].astype(np.int64)

    @property
    def tasks(self) -> np.ndarray:
        """The OB number that wrote each row (1 = OB1 scan)."""
        return self.table[:, 2].astype(np.int64)

    def column(self, name: str) -> np.ndarray:
        """The values of one signal, one per row (bool signals as a bool array)."""
        i = self._index.get(name)
        if i is None:
            raise UnknownTagError(
                f"the trace has no signal {name!r}{did_you_mean(name, self.names)}; traced: {', '.join(self.names)}"
            )
        col = self.table[:, HEAD + i]
        if self.types.get(name) == "bool":
            return col != 0.0
        return col

    def __contains__(self, name: object) -> bool:
        return name in self._index

    # -- tasks and order -------------------------------------------------------------------------

    def rows_of(self, task: str | int) -> np.ndarray:
        """The row numbers of one task's executions (``"OB1"``, ``"OB30"``), in order."""
        return np.flatnonzero(self.table[:, 2] == self.task_number(task))

    def task_number(self, task: str | int) -> int:
        """The task column's value for a task: its recorded number; a trace recorded without task names
        (made by hand, an old file) numbers S7 names (``"OB30"`` -> 30). 0 is the rows in STOP.

        >>> tr = TraceTable(["M"], task_numbers={"P12": 12})
        >>> tr.task_number("P12"), tr.task_number("OB30"), tr.task_number(1)
        (12, 30, 1)
        """
        if isinstance(task, int):
            return task
        number = self.task_numbers.get(task)
        return number if number is not None else trace_task_number(task)

    def of_task(self, task: str | int) -> TraceTable:
        """A trace of one task's rows only (names, meta and events shared): its times are in order."""
        view = type(self)(self.names, self.kinds, self.types, self.meta, self.events, task_numbers=self.task_numbers)
        view._blocks = [self.table[self.rows_of(task)]]
        return view

    def scan_after(self, t_ns: int, task: str | int = "OB1") -> int | None:
        """The row of the first execution of ``task`` that started at or after ``t_ns``: the scan that saw
        what happened at ``t_ns`` (an HMI write, a press, a sensor's new level). None if there is none."""
        rows = self.rows_of(task)
        k = int(np.searchsorted(self.times[rows], t_ns, side="left"))
        return int(rows[k]) if k < len(rows) else None

    def rows_started_by(self, t_ns: np.ndarray | int) -> np.ndarray:
        """For each time, the row whose execution started last at or before it (row 0 if none did):
        the scan in which a condition is read at that time, whatever the rows' order."""
        times = self.times
        order = self._start_order()
        ordered = times if order is None else times[order]
        k = np.clip(np.searchsorted(ordered, t_ns, side="right") - 1, 0, max(len(times) - 1, 0))
        return k if order is None else order[k]

    def _start_order(self) -> np.ndarray | None:
        """Row numbers sorted by start time (ties in recording order); None if the rows already are."""
        times = self.times
        if len(times) < 2 or bool(np.all(times[1:] >= times[:-1])):
            return None
        return np.argsort(times, kind="stable")

    def signal_times(self, name: str) -> np.ndarray:
        """When each row's value of ``name`` became valid: scan end for outputs, scan start otherwise."""
        return self.end_times if self.kinds.get(name) == "output" else self.times

    def value_at(self, name: str, t_ns: int, task: str | int | None = None) -> Any:
        """The value of a signal at time ``t_ns``: the row valid at or before it that became valid last
        (the first row if none is); with ``task``, among that task's rows only."""
        source = self if task is None else self.of_task(task)
        col = source.column(name)
        if len(col) == 0:
            raise ValueError("the trace is empty" if task is None else f"the trace has no row of {task}")
        when = source.signal_times(name)
        order = np.argsort(when, kind="stable")
        k = int(np.searchsorted(when[order], t_ns, side="right")) - 1
        value = col[order[max(k, 0)]]
        return bool(value) if self.types.get(name) == "bool" else value.item()

    def _edges(self, name: str, rising: bool) -> np.ndarray:
        col = self.column(name).astype(bool)
        if len(col) < 2:
            return np.zeros(0, dtype=np.int64)
        change = (col[1:] & ~col[:-1]) if rising else (~col[1:] & col[:-1])
        return np.nonzero(change)[0] + 1

    def rises(self, name: str) -> np.ndarray:
        """Times at which a Bool signal went FALSE -> TRUE."""
        return self.signal_times(name)[self._edges(name, True)]

    def falls(self, name: str) -> np.ndarray:
        """Times at which a Bool signal went TRUE -> FALSE."""
        return self.signal_times(name)[self._edges(name, False)]

    def rise_scans(self, name: str) -> np.ndarray:
        """Row numbers at which a Bool signal went FALSE -> TRUE."""
        return self._edges(name, True)

    def intervals(self, name: str, value: bool = True) -> list[tuple[int, int | None]]:
        """``[(start, end)]`` while a Bool signal had ``value``; the last end is None if it still has it."""
        col = self.column(name).astype(bool)
        if not value:
            col = ~col
        when = self.signal_times(name)
        out: list[tuple[int, int | None]] = []
        start = None
        for k in np.flatnonzero(np.diff(np.concatenate(([False], col, [False])).astype(np.int8))):
            if start is None:
                start = int(when[k])
            else:
                out.append((start, int(when[k]) if k < len(when) else None))
                start = None
        return out

    def events_of(
        self, kind: str | None = None, subject: str | None = None, source: str | None = None
    ) -> list[TraceEvent]:
        """Events filtered by kind, subject and source."""
        return [
            e
            for e in self.events
            if (kind is None or e.kind == kind)
            and (subject is None or e.subject == subject)
            and (source is None or e.source == source)
        ]

    @property
    def duration_ns(self) -> int:
        """Simulated time the trace covers."""
        return int(self.meta.get("end_ns", self.end_times[-1] if len(self) else 0))

    # -- files ---------------------------------------------------------------------------------

    def save(self, path: str | Path) -> Path:
        """Save as ``.npz``, every column named in the file itself (geometry is not saved).

        ``start_ns``, ``end_ns`` and ``task`` hold, per row (one execution of a task), its simulated start and
        end (int64 nanoseconds) and its task's number (``header``'s ``tasks`` names it, e.g. 1 for OB1);
        ``table`` is a structured array with one field per signal under its own name (a Bool as bool, an Int as
        int64, anything else float64); ``header`` is JSON: the signals' kinds and types, the run's meta and
        events. Read it back with :meth:`load`, or with numpy alone: ``np.load(path)["table"]["D1"]``.
        """
        path = Path(path)
        header = {
            "names": self.names,
            "kinds": self.kinds,
            "types": self.types,
            "meta": self.meta,
            "events": [asdict(e) for e in self.events],
            "tasks": self.task_numbers,
        }
        dense = self.table
        dtypes = [_SAVED_DTYPES.get(self.types.get(name), np.float64) for name in self.names]
        table = np.empty(len(dense), dtype=np.dtype(list(zip(self.names, dtypes, strict=True))))
        for k, name in enumerate(self.names):
            table[name] = dense[:, HEAD + k]
        heads = {name: dense[:, k].astype(np.int64) for k, name in enumerate(_HEAD_NAMES)}
        np.savez_compressed(path, table=table, header=np.array(json.dumps(header)), **heads)
        return path

    @classmethod
    def load(cls, path: str | Path) -> TraceTable:
        """Read a trace saved by :meth:`save` (or by plcsim 0.1, whose one table had unnamed columns)."""
        with np.load(Path(path)) as data:
            header = json.loads(str(data["header"]))
            trace = cls(
                header["names"],
                header["kinds"],
                header["types"],
                header["meta"],
                [TraceEvent(**e) for e in header["events"]],
                task_numbers=header.get("tasks", {}),
            )
            table = data["table"]
            if table.dtype.names is not None:
                columns = [data[name] for name in _HEAD_NAMES] + [table[name] for name in trace.names]
                table = np.column_stack([c.astype(np.float64) for c in columns]).reshape(len(table), -1)
            trace._blocks = [table]
        return trace

    def digest(self) -> str:
        """A hash of the rows and events, to prove two runs identical bit for bit."""
        import hashlib

        h = hashlib.sha256(self.table.tobytes())
        events = [{k: v for k, v in asdict(e).items() if k != "data"} for e in self.events]  # detail shows the data
        h.update(json.dumps(events).encode())
        return h.hexdigest()


def _scalar(value: Any) -> float | int | str | bool:
    """A value of a plant event's data as JSON keeps it (a number, a string or a bool; anything else as text)."""
    if isinstance(value, bool | int | float | str):
        return value
    if isinstance(value, np.integer | np.floating | np.bool_):
        return value.item()
    return str(value)


def _short(value: Any) -> str:
    return f"{value:.2f}" if isinstance(value, float) else str(value)


_OB_NAME = re.compile(r"^OB(\d+)$")


def trace_task_number(task: str) -> int:
    """The task column of an OB named in any case (``"ob30"`` -> 30): how the traces of plcsim 0.1, all
    of them from the S7, numbered their tasks before the task names were stored with the trace."""
    text = task.strip().upper()
    if _OB_NAME.match(text) is None:
        raise ValueError(f"the trace has no task named {task!r}; an S7 task is named like 'OB1' or 'OB30'")
    return int(text[2:])
