"""The trace's rows as they are written: the times of every row, its values only when they changed.

Most scans change no traced value (a machine at rest, a belt running between two sensors): such a row costs
the trace its times, and its values are the last stored ones. Each row is packed into bytes as it is
written (a Bool column as a signed byte, an Int as 8 bytes, a Real as a double: the exact value each holds),
so "changed" is a comparison of bytes, bit for bit (``0.0 == -0.0`` in Python, not in the table), and the
stored rows become numpy columns without a Python call per value. Reading expands them to the dense float64
table of :class:`plcsim.trace.table.TraceTable`, the same bit for bit as converting every row's values with
``np.float64``. A row with a value its column's code cannot hold (an Int column given 2.5, a None) is kept
as a tuple, stored whatever the last row was, and converted as numpy converts it.

A row of a *regular* execution (:attr:`RunLengthRows.regular`: one scan per physics step, the case of almost
every row of a co-simulation) keeps no head at all but its start time, an ``int``: its end and task follow
from the regular step and task, and :meth:`RunLengthRows.pack` derives them, so the hot path packs no head.

>>> rows = RunLengthRows("bd")
>>> for k, values in enumerate([(False, 0.0), (False, 0.0), (True, 0.0), (True, -0.0), (True, -0.0)]):
...     rows.add(k, k + 1, 1, values)
>>> len(rows), rows.stored
(5, 3)
>>> rows.take()[:, 3:].tolist()
[[0.0, 0.0], [0.0, 0.0], [1.0, 0.0], [1.0, -0.0], [1.0, -0.0]]
"""

from __future__ import annotations

import struct
from collections.abc import Callable
from itertools import chain
from typing import Any

import numpy as np

BLOCK = 4096
"""Rows converted to numpy at a time."""
HEAD = 3
"""Leading columns of every row: scan start, scan end, task number."""
UNSET: Any = object()
"""The last values before any row: differs from every row's, so the first row's values are stored."""
UNPACKABLE = (struct.error, TypeError, OverflowError, ValueError)
"""What packing a value its column's code cannot hold raises."""

_HEAD = struct.Struct("<qqq")
_DTYPES = {"b": "i1", "q": "<i8", "d": "<f8"}


class RunLengthRows:
    """The rows of a trace being written; :meth:`take` hands them over as one dense array.

    A writer appends to :attr:`heads` (a row's ``(start, end, task)``, packed by :attr:`pack_head`, or a regular
    row's start alone) and, when
    the row's values packed by :attr:`pack_values` differ from :attr:`last` ``[0]``, to :attr:`values` and
    :attr:`changes` (the row's place in ``heads``); it calls :meth:`pack` when ``heads`` holds :data:`BLOCK`
    rows. :meth:`add` does all that; a recorder's hot path does it inline.

    Args:
        codes: one :mod:`struct` code per column: ``b`` (Bool), ``q`` (Int), ``d`` (Real).
    """

    __slots__ = (
        "width",
        "pack_head",
        "pack_values",
        "heads",
        "values",
        "changes",
        "last",
        "_values_format",
        "_dtype",
        "_heads",
        "_values",
        "_changes",
        "_rows",
        "regular",
    )

    def __init__(self, codes: str):
        self.width = len(codes)
        self._values_format = struct.Struct("<" + codes)
        self._dtype = np.dtype([(f"c{k}", _DTYPES[code]) for k, code in enumerate(codes)])
        self.pack_head: Callable[..., bytes] = _HEAD.pack
        self.pack_values: Callable[..., bytes] = self._values_format.pack
        self.heads: list[bytes | tuple[Any, ...]] = []
        self.values: list[bytes | tuple[Any, ...]] = []
        self.changes: list[int] = []
        self.last: list[Any] = [UNSET]
        """The last stored values, in a list that the writers share."""
        self._heads: list[np.ndarray] = []
        self._values: list[np.ndarray] = []
        self._changes: list[np.ndarray] = []
        self._rows = 0
        self.regular: tuple[int, int] = (0, 0)
        """``(duration, task)`` of the rows whose head is their start time alone (an ``int`` in :attr:`heads`);
        change it only with no such row unpacked (:meth:`set_regular`)."""

    def set_regular(self, duration_ns: int, task: int) -> None:
        """Make the rows appended from now on as a start time alone last ``duration_ns`` and belong to ``task``."""
        if (duration_ns, task) != self.regular:
            self.pack()
            self.regular = (duration_ns, task)

    def add(self, t_ns: int, t_end_ns: int, task: int, values: tuple[Any, ...]) -> None:
        """Append one row."""
        heads = self.heads
        try:
            heads.append(self.pack_head(t_ns, t_end_ns, task))
        except UNPACKABLE:
            heads.append((t_ns, t_end_ns, task))
        try:
            packed: bytes | tuple[Any, ...] = self.pack_values(*values)
            changed = packed != self.last[0]
        except UNPACKABLE:
            packed, changed = values, True
        if changed:
            self.last[0] = packed
            self.changes.append(len(heads) - 1)
            self.values.append(packed)
        if len(heads) >= BLOCK:
            self.pack()

    def pack(self) -> None:
        """Convert the rows appended since the last pack to numpy blocks."""
        heads = self.heads
        if not heads:
            return
        self._heads.append(self._head_floats(heads))
        if self.values:
            self._values.append(self._floats(self.values, self._values_format, self._dtype))
            self._changes.append(np.array(self.changes, dtype=np.int64) + self._rows)
        self._rows += len(heads)
        heads.clear()
        self.values.clear()
        self.changes.clear()

    def take(self) -> np.ndarray:
        """Every row so far as a dense (rows, 3 + width) float64 array; the store is empty after it (the next
        row's values are stored, whatever they are)."""
        self.pack()
        rows = self._rows
        dense = np.empty((rows, HEAD + self.width))
        if rows:
            changes = np.concatenate(self._changes)
            dense[:, :HEAD] = np.concatenate(self._heads)
            dense[:, HEAD:] = np.repeat(np.concatenate(self._values), np.diff(changes, append=rows), axis=0)
        self._heads, self._values, self._changes, self._rows = [], [], [], 0
        self.last[0] = UNSET
        return dense

    @property
    def stored(self) -> int:
        """How many rows' values are stored (the others repeat the row before)."""
        return sum(map(len, self._values)) + len(self.values)

    def __len__(self) -> int:
        return self._rows + len(self.heads)

    def _head_floats(self, heads: list[Any]) -> np.ndarray:
        """The heads as a (rows, 3) float64 array, those of regular rows (a start time alone) derived."""
        duration, task = self.regular
        kinds = set(map(type, heads))
        if kinds == {int}:  # every row regular (a co-simulation's block): three columns from the start times
            starts = np.fromiter(heads, np.int64, len(heads))
            return np.column_stack((starts, starts + duration, np.full(len(starts), task, np.int64))).astype(np.float64)
        if int in kinds:
            heads = [_HEAD.pack(head, head + duration, task) if type(head) is int else head for head in heads]
        return self._floats(heads, _HEAD, np.dtype((np.int64, HEAD)))

    @staticmethod
    def _floats(items: list[bytes | tuple[Any, ...]], layout: struct.Struct, dtype: np.dtype) -> np.ndarray:
        """Packed rows (and rows kept as tuples) as a (rows, columns) float64 array."""
        width = len(dtype.names) if dtype.names is not None else dtype.shape[0]
        try:
            buffer = b"".join(items)  # type: ignore[arg-type]
        except TypeError:  # a row kept as a tuple: every row as values, converted as numpy converts them
            return _converted([layout.unpack(item) if isinstance(item, bytes) else item for item in items], width)
        packed = np.frombuffer(buffer, dtype) if width else np.zeros(len(items), dtype)
        if dtype.names is None:
            return packed.astype(np.float64)
        out = np.empty((len(packed), width))
        for k, name in enumerate(dtype.names):
            out[:, k] = packed[name]
        return out


def _converted(rows: list[tuple[Any, ...]], width: int) -> np.ndarray:
    """Rows of Python numbers as a (rows, width) float64 array, each value converted by ``np.float64``."""
    count = len(rows) * width
    if sum(map(len, rows)) == count:  # every row as wide as the table: read them as one stream
        try:  # the same float64 conversion of each value as np.array's, a third cheaper
            return np.fromiter(chain.from_iterable(rows), np.float64, count).reshape(len(rows), width)
        except (TypeError, ValueError):  # a value fromiter cannot convert (None): numpy's general path
            pass
    return np.array(rows, dtype=np.float64).reshape(len(rows), width)
