"""What running a submission produces, and the checked byte format a sandboxed child sends it in.

A :class:`RunResult` is the raw outcome of one scenario: the trace (columns, times, tasks, events,
optionally the plant's geometry), the CPU's mode, error and warnings, and the run's length. It holds
no score: the checks run in the grader on it (see :mod:`plcsim.grading.scoring`).

The child's message is ``MAGIC``, an 8-byte header length, a JSON header and the raw float64 row
tables. Nothing in it is unpickled or executed; :func:`decode` accepts it only if it has exactly the
scenarios, seed, signals, kinds and types the grader expects, times inside each scenario's horizon,
0/1 in Bool columns and bounded sizes. Anything else is an :class:`InvalidResultError`.
"""

from __future__ import annotations

import json
import math
import struct
from collections.abc import Mapping, Sequence
from dataclasses import asdict, dataclass, field
from typing import Any

import numpy as np

from plcsim.core.errors import PlcError
from plcsim.core.untrusted_text import clip
from plcsim.plant.protocol import Drawable
from plcsim.trace.facade import HEAD, GeometryFrame, Trace, TraceEvent

MAGIC = b"PLCSIM-RESULT-1\n"
LENGTH = struct.Struct(">Q")
MAX_HEADER_BYTES = 256 * 1024 * 1024
MAX_TEXT = 20_000
"""Longest string accepted from a child (a message, an event detail, a name)."""
MAX_LIST = 2_000_000
"""Most events, warnings or geometry items accepted per scenario."""
EVENT_SOURCES = frozenset({"plant", "scenario", "cpu", "wiring"})
CPU_MODES = frozenset({"RUN", "STOP"})
SIGNAL_TYPES = frozenset({"bool", "int", "real"})
SIGNAL_KINDS = frozenset({"input", "output", "memory", "db", "timer", "counter", "analog"})
DRAWABLE_KINDS = frozenset({"polygon", "line", "circle", "label"})
EXTRA_COLUMNS = 2_000
"""Columns a child may trace beyond the exercise's (the program's own tags); they are not graded."""


class InvalidResultError(PlcError):
    """A child's result that is malformed or not what the grader asked for; it never earns a point."""


@dataclass
class RunResult:
    """How one scenario ran: the trace and the CPU's state at the end."""

    scenario: str
    seed: int
    trace: Trace
    simulated_ns: int
    scans: int
    cpu_mode: str
    cpu_error: str | None = None
    plant_error: str | None = None
    warnings: list[str] = field(default_factory=list)


@dataclass(frozen=True)
class Expected:
    """What the grader expects of one scenario's result: computed in the grader, never sent by the child.

    Attributes:
        scenario: its name.
        horizon_ns: the scenario's duration; no time may lie beyond it.
        max_rows: the most trace rows the run can produce.
        kinds: required signal -> kind; types: required signal -> type.
        meta: the trace's meta data as the grader knows it (seed, cycle, dt ...).
    """

    scenario: str
    horizon_ns: int
    max_rows: int
    kinds: Mapping[str, str]
    types: Mapping[str, str]
    meta: Mapping[str, Any]


# -- encoding (in the child) -------------------------------------------------------------------------


def encode_runs(runs: Sequence[RunResult], *, geometry: bool = False) -> bytes:
    """The message of a child that ran every scenario (``geometry``: also the plant's shapes)."""
    header_runs, blobs = [], []
    for run in runs:
        table = np.ascontiguousarray(run.trace.table, dtype="<f8")
        tr = run.trace
        entry: dict[str, Any] = {
            "scenario": run.scenario,
            "seed": run.seed,
            "simulated_ns": run.simulated_ns,
            "scans": run.scans,
            "cpu_mode": run.cpu_mode,
            "cpu_error": None if run.cpu_error is None else clip(run.cpu_error, MAX_TEXT),
            "plant_error": None if run.plant_error is None else clip(run.plant_error, MAX_TEXT),
            "warnings": [clip(w, MAX_TEXT) for w in run.warnings],
            "names": list(tr.names),
            "kinds": dict(tr.kinds),
            "types": dict(tr.types),
            "events": [asdict(e) for e in tr.events],
            "rows": int(table.shape[0]),
        }
        if geometry:
            entry["frames"] = [[f.t_ns, [_drawable(d) for d in f.drawables]] for f in tr.frames]
            entry["static"] = [_drawable(d) for d in tr.static_drawables]
            entry["bounds"] = list(tr.bounds) if tr.bounds is not None else None
        header_runs.append(entry)
        blobs.append(table.tobytes())
    return _frame({"kind": "runs", "runs": header_runs}, blobs)


def encode_failure(kind: str, message: str) -> bytes:
    """The message of a child whose submission did not run (it did not load, or ran out of memory); a
    message longer than the grader accepts (a label of 3 MB echoed by an error) arrives cut, saying so."""
    return _frame({"kind": "failure", "error_kind": kind, "message": clip(message, MAX_TEXT)}, [])


def _frame(header: dict[str, Any], blobs: Sequence[bytes]) -> bytes:
    head = json.dumps(header, allow_nan=False).encode("utf-8")
    return b"".join([MAGIC, LENGTH.pack(len(head)), head, *blobs])


def _drawable(d: Drawable) -> dict[str, Any]:
    points = np.asarray(d.points, dtype=float).reshape(-1, 2)
    return {
        "path": d.path,
        "kind": d.kind,
        "points": points.tolist(),
        "color": [int(c) for c in d.color],
        "radius": float(d.radius),
        "text": d.text,
    }


# -- decoding (in the grader) ------------------------------------------------------------------------


def message_length(buffer: bytes | bytearray) -> int | None:
    """The total length of the message that starts ``buffer`` (None while the header is incomplete).

    Raises InvalidResultError at once for a buffer that does not start like a message, so that a
    hostile child cannot make the grader wait for bytes that never come.
    """
    if len(buffer) < len(MAGIC) + LENGTH.size:
        if not MAGIC.startswith(buffer[: len(MAGIC)]):
            raise InvalidResultError("the child's result does not start with the result marker")
        return None
    if not buffer.startswith(MAGIC):
        raise InvalidResultError("the child's result does not start with the result marker")
    (head_len,) = LENGTH.unpack_from(buffer, len(MAGIC))
    if head_len > MAX_HEADER_BYTES:
        raise InvalidResultError(f"the child's result header has {head_len} bytes; at most {MAX_HEADER_BYTES}")
    start = len(MAGIC) + LENGTH.size
    if len(buffer) < start + head_len:
        return None
    header = _header(buffer, start, head_len)
    if header.get("kind") == "failure":
        return start + head_len
    if header.get("kind") != "runs" or set(header) != {"kind", "runs"}:
        fields = _short(sorted(header)[:8])
        raise InvalidResultError(f"the child's result is not a runs or failure message (fields {fields})")
    runs = header.get("runs")
    if not isinstance(runs, list):
        raise InvalidResultError("the child's result has no list of runs")
    total = start + head_len
    for run in runs:
        if not isinstance(run, dict):
            raise InvalidResultError("a run of the child's result is not an object")
        rows, names = run.get("rows"), run.get("names")
        if not _is_int(rows) or rows < 0 or not isinstance(names, list):
            raise InvalidResultError("a run of the child's result has no row count or signal names")
        total += rows * (HEAD + len(names)) * 8
    return total


def _header(buffer: bytes | bytearray, start: int, length: int) -> dict[str, Any]:
    try:
        header = json.loads(buffer[start : start + length].decode("utf-8"), parse_constant=_no_constant)
    except (UnicodeDecodeError, ValueError) as exc:
        raise InvalidResultError(f"the child's result header is not valid JSON: {exc}") from None
    if not isinstance(header, dict):
        raise InvalidResultError("the child's result header is not an object")
    return header


def _no_constant(name: str) -> Any:
    raise ValueError(f"{name} is not allowed")


def decode(buffer: bytes, expected: Sequence[Expected], seed: int) -> list[RunResult] | tuple[str, str]:
    """The runs in a child's message, checked against what the grader expects; or (kind, message) of
    a child that reports its submission could not run. Raises InvalidResultError for anything else."""
    total = message_length(buffer)
    if total is None or len(buffer) != total:
        raise InvalidResultError(f"the child's result has {len(buffer)} bytes; its header announces {total}")
    start = len(MAGIC) + LENGTH.size
    (head_len,) = LENGTH.unpack_from(buffer, len(MAGIC))
    header = _header(buffer, start, head_len)
    if header.get("kind") == "failure":
        kind, message = header.get("error_kind"), header.get("message")
        if kind not in ("subset violation", "program error", "memory limit", "crash", "grader error"):
            raise InvalidResultError(f"the child reports an unknown failure kind {_short(kind)}")
        return kind, _text(message, "failure message")
    runs = header["runs"]
    if [r.get("scenario") for r in runs] != [e.scenario for e in expected]:
        raise InvalidResultError(
            f"the child's result has the scenarios {_short([r.get('scenario') for r in runs])}; "
            f"expected {[e.scenario for e in expected]}"
        )
    offset = start + head_len
    out = []
    for entry, exp in zip(runs, expected):
        width = HEAD + len(entry["names"])
        nbytes = entry["rows"] * width * 8
        table = np.frombuffer(buffer, dtype="<f8", count=entry["rows"] * width, offset=offset)
        offset += nbytes
        out.append(_run(entry, table.reshape(entry["rows"], width).astype(np.float64), exp, seed))
    return out


def _run(entry: dict[str, Any], table: np.ndarray, exp: Expected, seed: int) -> RunResult:
    where = f"scenario {exp.scenario!r}"
    if entry.get("seed") != seed:
        raise InvalidResultError(f"{where}: the child ran seed {_short(entry.get('seed'))}, not {seed}")
    simulated = entry.get("simulated_ns")
    if not _is_int(simulated) or not 0 <= simulated <= exp.horizon_ns:
        raise InvalidResultError(f"{where}: simulated time {_short(simulated)} is outside 0..{exp.horizon_ns} ns")
    scans = entry.get("scans")
    if not _is_int(scans) or not 0 <= scans <= exp.max_rows:
        raise InvalidResultError(f"{where}: scan count {_short(scans)} is impossible")
    mode = entry.get("cpu_mode")
    if mode not in CPU_MODES:
        raise InvalidResultError(f"{where}: CPU mode {_short(mode)} is neither RUN nor STOP")
    names, kinds, types = entry.get("names"), entry.get("kinds"), entry.get("types")
    if not (isinstance(names, list) and all(isinstance(n, str) and 0 < len(n) <= 200 for n in names)):
        raise InvalidResultError(f"{where}: the signal names are not a list of short strings")
    if len(names) > len(exp.kinds) + EXTRA_COLUMNS:
        raise InvalidResultError(f"{where}: {len(names)} traced signals; the exercise has {len(exp.kinds)}")
    if len(set(names)) != len(names) or not isinstance(kinds, dict) or not isinstance(types, dict):
        raise InvalidResultError(f"{where}: the signal names repeat, or kinds and types are missing")
    if set(kinds) != set(names) or set(types) != set(names):
        raise InvalidResultError(f"{where}: kinds and types do not name exactly the traced signals")
    if not set(kinds.values()) <= SIGNAL_KINDS or not set(types.values()) <= SIGNAL_TYPES:
        raise InvalidResultError(f"{where}: unknown signal kinds or types")
    missing = [n for n in exp.kinds if n not in kinds]
    if missing:
        raise InvalidResultError(f"{where}: the trace lacks the exercise's signals {missing[:10]}")
    wrong = [n for n in exp.kinds if (kinds[n], types[n]) != (exp.kinds[n], exp.types[n])]
    if wrong:
        raise InvalidResultError(f"{where}: the signals {wrong[:10]} have the wrong kind or type")
    if entry["rows"] > exp.max_rows:
        raise InvalidResultError(f"{where}: {entry['rows']} trace rows; the scenario allows at most {exp.max_rows}")
    _check_table(table, names, types, simulated, where)
    events = entry.get("events")
    if not isinstance(events, list) or len(events) > MAX_LIST:
        raise InvalidResultError(f"{where}: the events are not a bounded list")
    trace = Trace(list(exp.kinds), dict(exp.kinds), dict(exp.types), dict(exp.meta))
    trace.meta.update({"end_ns": simulated, "scans": scans})
    trace.events = [_event(e, simulated, where) for e in events]
    column = {name: HEAD + k for k, name in enumerate(names)}
    keep = [column[n] for n in exp.kinds]
    trace._blocks = [np.ascontiguousarray(table[:, list(range(HEAD)) + keep])] if len(table) else []
    if "frames" in entry:
        _geometry(trace, entry, simulated, where)
    warnings = entry.get("warnings")
    if not isinstance(warnings, list) or len(warnings) > MAX_LIST:
        raise InvalidResultError(f"{where}: the warnings are not a bounded list")
    return RunResult(
        exp.scenario,
        seed,
        trace,
        simulated,
        scans,
        mode,
        _optional_text(entry.get("cpu_error"), "CPU error"),
        _optional_text(entry.get("plant_error"), "plant error"),
        [_text(w, "warning") for w in warnings],
    )


def _check_table(table: np.ndarray, names: list[str], types: dict[str, str], horizon: int, where: str) -> None:
    if not len(table):
        return
    head = table[:, :HEAD]
    if not np.isfinite(head).all() or (head != np.round(head)).any():
        raise InvalidResultError(f"{where}: trace times and task numbers must be whole numbers")
    start, end, task = head[:, 0], head[:, 1], head[:, 2]
    if (start < 0).any() or (end < start).any() or (end > horizon).any():
        raise InvalidResultError(f"{where}: a trace row lies outside 0..{horizon} ns or ends before it starts")
    if (np.diff(end) < 0).any():
        raise InvalidResultError(f"{where}: trace rows are not in the order their scans ended")
    if (task < 0).any() or (task > 1000).any():
        raise InvalidResultError(f"{where}: a trace row names an impossible task")
    for k, name in enumerate(names):
        col = table[:, HEAD + k]
        kind = types[name]
        if kind == "bool" and not np.isin(col, (0.0, 1.0)).all():
            raise InvalidResultError(f"{where}: the Bool signal {name!r} holds values other than 0 and 1")
        if kind == "int" and (not np.isfinite(col).all() or (col != np.round(col)).any()):
            raise InvalidResultError(f"{where}: the integer signal {name!r} holds non-integer values")


def _event(e: Any, horizon: int, where: str) -> TraceEvent:
    if not isinstance(e, dict) or set(e) != {"t_ns", "source", "kind", "subject", "part", "detail", "data"}:
        raise InvalidResultError(f"{where}: an event does not have the fields of a trace event")
    data = e["data"]
    if not isinstance(data, dict) or len(data) > 64 or not all(_is_datum(k, v) for k, v in data.items()):
        raise InvalidResultError(f"{where}: an event's data is not a small table of numbers and texts")
    if not _is_int(e["t_ns"]) or not 0 <= e["t_ns"] <= horizon or e["source"] not in EVENT_SOURCES:
        raise InvalidResultError(f"{where}: an event has an impossible time or source")
    return TraceEvent(
        e["t_ns"],
        e["source"],
        _text(e["kind"], "event kind"),
        _text(e["subject"], "event subject"),
        _optional_text(e["part"], "event part"),
        _text(e["detail"], "event detail"),
        dict(data),
    )


def _is_datum(key: Any, value: Any) -> bool:
    """A key and value of a plant event's data: a short name, and a finite number, a bool or a short text."""
    if not isinstance(key, str) or len(key) > 100:
        return False
    if isinstance(value, str):
        return len(value) <= 1000
    return isinstance(value, bool | int) or (isinstance(value, float) and math.isfinite(value))


def _geometry(trace: Trace, entry: dict[str, Any], horizon: int, where: str) -> None:
    frames, static, bounds = entry.get("frames"), entry.get("static"), entry.get("bounds")
    if not isinstance(frames, list) or not isinstance(static, list) or len(frames) > MAX_LIST:
        raise InvalidResultError(f"{where}: the geometry is not a bounded list of frames")
    for f in frames:
        if not (isinstance(f, list) and len(f) == 2 and _is_int(f[0]) and 0 <= f[0] <= horizon):
            raise InvalidResultError(f"{where}: a geometry frame has an impossible time")
        trace.frames.append(GeometryFrame(f[0], [_decode_drawable(d, where) for d in _bounded(f[1], where)]))
    trace.static_drawables = [_decode_drawable(d, where) for d in _bounded(static, where)]
    if bounds is not None:
        if not (isinstance(bounds, list) and len(bounds) == 4 and all(_is_finite(v) for v in bounds)):
            raise InvalidResultError(f"{where}: the plant bounds are not four numbers")
        trace.bounds = tuple(float(v) for v in bounds)  # type: ignore[assignment]


def _bounded(items: Any, where: str) -> list[Any]:
    if not isinstance(items, list) or len(items) > 10_000:
        raise InvalidResultError(f"{where}: a geometry frame is not a bounded list")
    return items


def _decode_drawable(d: Any, where: str) -> Drawable:
    ok = isinstance(d, dict) and set(d) == {"path", "kind", "points", "color", "radius", "text"}
    if ok:
        points, color = d["points"], d["color"]
        ok = (
            d["kind"] in DRAWABLE_KINDS
            and isinstance(points, list)
            and len(points) <= 10_000
            and all(isinstance(p, list) and len(p) == 2 and all(_is_finite(v) for v in p) for p in points)
            and isinstance(color, list)
            and len(color) == 3
            and all(_is_int(c) and 0 <= c <= 255 for c in color)
            and _is_finite(d["radius"])
        )
    if not ok:
        raise InvalidResultError(f"{where}: a drawable of the geometry is malformed")
    return Drawable(
        _text(d["path"], "drawable path"),
        d["kind"],
        np.array(d["points"], dtype=float).reshape(-1, 2),
        tuple(d["color"]),
        float(d["radius"]),
        _text(d["text"], "drawable text"),
    )


def _is_int(value: Any) -> bool:
    return isinstance(value, int) and not isinstance(value, bool)


def _is_finite(value: Any) -> bool:
    return isinstance(value, (int, float)) and not isinstance(value, bool) and math.isfinite(value)


def _text(value: Any, what: str) -> str:
    if not isinstance(value, str) or len(value) > MAX_TEXT:
        raise InvalidResultError(f"the child's {what} is not a string of at most {MAX_TEXT} characters")
    return value


def _optional_text(value: Any, what: str) -> str | None:
    return None if value is None else _text(value, what)


def _short(value: Any) -> str:
    text = repr(value)
    return text if len(text) <= 80 else text[:77] + "..."
