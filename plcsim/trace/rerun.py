"""Export a :class:`~plcsim.trace.facade.Trace` to a rerun ``.rrd`` file a student opens with ``rerun FILE.rrd``.

The file holds one timeline, ``sim``, in simulated time (no wall-clock time), and a blueprint that
shows the machine beside or above the signals:

* ``meta`` — a text document: exercise, scenario, seed, program, and the traced signals;
* ``signals/inputs/<name>``, ``signals/outputs/<name>``, ``signals/internal/<name>`` — each Bool as a
  0/1 step series in its own entity, shown in its own lane (like a logic analyser: lines of one
  shared 0/1 plot lie on top of each other); inputs at scan start, outputs at scan end (when each
  became valid, see :meth:`Trace.signal_times`), internal tags at scan start;
* ``signals/numbers`` (and ``signals/numbers/outputs`` for numeric outputs) — Int/Real tags,
  timer ETs and counter values as step series;
* ``signals/analog`` — a plant's measured values (kind ``analog``: a press's ram height) as lines
  through their samples, as in the PNG timing diagram;
* ``events/plant``, ``events/cpu``, ``events/scenario``, ... — the events as a text log with levels
  (plant events INFO, mishaps such as a part falling off WARN, CPU errors ERROR, STOP WARN,
  scenario actions DEBUG);
* ``plant/static/<path>`` — the shapes that never move, logged once (static);
* ``plant/moving/<group>`` — the sampled geometry frames, one entity per first path segment
  (``parts``, ``beams``, ...), one batch of shapes per frame.

Each text is drawn once: a plant names a sensor by its label and again as the caption of its line
and its beam; a caption is drawn only where no label or fixed shape writes the same text.

Plant coordinates are mm with y up; rerun's 2D view is y down, so y is negated.

Everything is sent as columns (one ``send_columns`` per entity), never one log call per signal per
scan. The series are exact step functions at any zoom: at each change the held value and then the
new value are sent at the same time (so a line joins only equal values), and the viewer's
aggregation is off (it would average a one-scan pulse with its neighbours into a 0.5 plateau).
By default only the first row, the changes and the last row are sent; pass ``every_row=True`` to
keep every scan.

The recording id is derived from the trace's metadata and content, so the same trace always gives
the same recording id and the same data. The files are not byte-identical: rerun stamps every row
and chunk with a fresh id.
"""

from __future__ import annotations

import json
import os
import uuid
import warnings
from collections.abc import Iterator, Sequence
from contextlib import contextmanager
from functools import lru_cache
from pathlib import Path
from typing import Any

import numpy as np

from plcsim.plant.protocol import Drawable
from plcsim.trace.table import HEAD, TraceEvent, TraceTable

TIMELINE = "sim"
"""The one timeline of an exported recording (simulated time)."""

GROUPS: dict[str, str] = {
    "inputs": "signals/inputs",
    "outputs": "signals/outputs",
    "internal": "signals/internal",
    "numbers": "signals/numbers",
    "number_outputs": "signals/numbers/outputs",
    "analog": "signals/analog",
}
"""Signal group -> entity path."""

BOOL_GROUPS = ("inputs", "outputs", "internal")
"""The groups drawn one lane per signal, like a logic analyser."""

LANE_COLORS: dict[str, int] = {
    "inputs": 0x2B8A3EFF,
    "outputs": 0xC92A2AFF,
    "internal": 0x1864ABFF,
    "analog": 0xE8590CFF,
}
"""Lane colours by group, as in the PNG timing diagram (:mod:`plcsim.trace.plot`)."""

GROUP_TITLES: dict[str, str] = {
    "inputs": "Inputs (I)",
    "outputs": "Outputs (Q)",
    "internal": "Internal bits (M, DB, timers, counters)",
    "numbers": "Numbers",
    "analog": "Plant measurements",
}

_NAMESPACE = uuid.UUID("6b1f6c1e-2f5e-4c11-9a57-706c6373696d")
_PLANT_MISHAPS = {"part fell off", "part jammed", "motor jammed", "interlock violated", "end stop hit"}
_CPU_ERRORS = {"error in the program", "cycle time monitoring exceeded"}
_CPU_WARNINGS = {"RUN->STOP", "cyclic interrupt overrun", "force", "warning"}

# draw orders: fixed shapes below moving ones, labels on top
_STATIC_LINES, _STATIC_POINTS, _MOVING_LINES, _MOVING_POINTS = 10.0, 11.0, 20.0, 21.0
_LINE_RADIUS = -1.0  # negative: UI points, so lines stay visible at any zoom
_LABEL_RADIUS = -0.5  # a label is its text; the anchor dot stays small


def export_rrd(
    trace: TraceTable,
    path: str | Path,
    *,
    application_id: str = "plcsim",
    recording_id: str | None = None,
    title: str | None = None,
    every_row: bool = False,
) -> Path:
    """Write ``trace`` to a rerun recording at ``path`` and return the path.

    Args:
        trace: the run to export.
        path: the ``.rrd`` file to write (its folder must exist).
        application_id: rerun's application id (recordings with the same id share a viewer layout).
        recording_id: default: derived from ``trace.meta`` and the trace's digest, so the same trace
            always gets the same id and two different runs never merge in the viewer.
        title: the recording's name in the viewer (default: from the metadata).
        every_row: send every trace row rather than only the rows where a group's value changed.

    The export is an explicit request for a file, so it is written even when ``RERUN=off`` is set
    (that variable silences live logging, not exports). Data rerun cannot convert raises instead of
    being dropped with a warning.
    """
    import rerun as rr
    from rerun.error_utils import RerunWarning

    path = Path(path)
    rid = recording_id or default_recording_id(trace)
    with warnings.catch_warnings():
        warnings.simplefilter("error", RerunWarning)
        return _export(rr, trace, path, application_id, rid, title, every_row)


def _export(
    rr: Any, trace: TraceTable, path: Path, application_id: str, rid: str, title: str | None, every_row: bool
) -> Path:
    with _rerun_enabled():  # the recording and the blueprint's stream, both created here
        rec = rr.RecordingStream(application_id, recording_id=rid, send_properties=False)
        rec.set_log_time_enabled(False)
        rec.set_log_tick_enabled(False)
        rec.save(path, default_blueprint=make_blueprint(trace))
    try:
        rec.send_recording_name(title or _default_title(trace))
        rec.log("meta", rr.TextDocument(metadata_markdown(trace), media_type="text/markdown"), static=True)
        _send_signals(rec, trace, every_row)
        _send_events(rec, trace.events)
        written = _send_static_geometry(rec, trace.static_drawables)
        _send_frames(rec, trace, written)
        rec.flush()
    finally:
        rec.disconnect()
    return path


# -- identity and metadata ---------------------------------------------------------------------


def default_recording_id(trace: TraceTable) -> str:
    """A recording id that depends only on the trace: its metadata and its rows and events."""
    meta = json.dumps(trace.meta, sort_keys=True, default=str)
    return str(uuid.uuid5(_NAMESPACE, f"{meta}\n{trace.digest()}"))


def _default_title(trace: TraceTable) -> str:
    meta = trace.meta
    parts = [
        str(meta[k]) for k in ("exercise", "scenario", "plant", "program") if meta.get(k) and str(meta[k])[0] != "<"
    ]
    seed = meta.get("seed")
    return " · ".join(parts + ([f"seed {seed}"] if seed is not None else [])) or "plcsim run"


def metadata_markdown(trace: TraceTable) -> str:
    """The run's description shown in the viewer: metadata and the traced signals."""
    meta = trace.meta
    lines = ["# plcsim run", "", "| | |", "|---|---|"]
    first = [k for k in ("exercise", "scenario", "plant", "program", "seed") if k in meta]
    for key in first + sorted(k for k in meta if k not in first):
        value = meta[key]
        if key.endswith("_ns") and isinstance(value, int):
            value = f"{value / 1e9:g} s"
        lines.append(f"| {key} | {_md(value)} |")
    lines.append(f"| rows | {len(trace)} |")
    lines += ["", "## Signals", "", "| signal | kind | type |", "|---|---|---|"]
    lines += [f"| {_md(n)} | {trace.kinds.get(n, '')} | {trace.types.get(n, '')} |" for n in trace.names]
    return "\n".join(lines) + "\n"


def _md(value: Any) -> str:
    return str(value).replace("|", "\\|").replace("\n", " ")


@contextmanager
def _rerun_enabled() -> Iterator[None]:
    """Hide ``RERUN=off`` while the streams are created (rerun reads it only then)."""
    saved = os.environ.pop("RERUN", None)
    try:
        yield
    finally:
        if saved is not None:
            os.environ["RERUN"] = saved


# -- signals -----------------------------------------------------------------------------------


def signal_groups(trace: TraceTable) -> dict[str, list[str]]:
    """The trace's signals by group (``inputs``, ``outputs``, ``internal``, ``numbers``,
    ``number_outputs``, ``analog``), in trace order; empty groups are left out."""
    groups: dict[str, list[str]] = {g: [] for g in GROUPS}
    for name in trace.names:
        kind = trace.kinds.get(name, "memory")
        if kind == "analog":
            group = "analog"
        elif trace.types.get(name) == "bool":
            group = {"input": "inputs", "output": "outputs"}.get(kind, "internal")
        else:
            group = "number_outputs" if kind == "output" else "numbers"
        groups[group].append(name)
    return {g: names for g, names in groups.items() if names}


def lane_entity(group: str, name: str) -> str:
    """The entity of one Bool signal's lane: ``signals/inputs/S1`` (the name escaped, so ``TON_A.Q``
    and ``TON_A_Q`` stay apart)."""
    import rerun as rr

    return f"{GROUPS[group]}/{rr.escape_entity_path_part(name)}"


def step_rows(times: np.ndarray, values: np.ndarray, every_row: bool = False) -> tuple[np.ndarray, np.ndarray]:
    """A step function's rows, exact at any zoom: the first row, at each change the held value and
    then the new value at the same time (so a line joins only equal values, even where the viewer
    interpolates linearly or aggregates), and the last row; ``every_row`` keeps the rows between.

    >>> t, v = step_rows(np.array([0, 1, 2, 3]), np.array([[0.0], [1.0], [0.0], [0.0]]))
    >>> t.tolist(), v[:, 0].tolist()
    ([0, 1, 1, 2, 2, 3], [0.0, 0.0, 1.0, 1.0, 0.0, 0.0])
    """
    n = len(values)
    if n == 0:
        return times[:0], values[:0]
    changed = np.zeros(n, dtype=bool)
    changed[1:] = np.any(values[1:] != values[:-1], axis=1)
    keep = changed.copy() if not every_row else np.ones(n, dtype=bool)
    keep[0] = keep[-1] = True
    rows = np.flatnonzero(keep)
    held = changed[rows]  # rows that get the value held before them, at their own time
    order = np.repeat(rows, 1 + held)  # a changed row appears twice: held value, then its own
    first = np.ones(len(order), dtype=bool)
    first[1:] = order[1:] != order[:-1]
    source = order.copy()
    source[first & np.repeat(held, 1 + held)] -= 1  # the first copy of a changed row shows the row before
    return times[order], values[source]


def line_rows(times: np.ndarray, values: np.ndarray, every_row: bool = False) -> tuple[np.ndarray, np.ndarray]:
    """A sampled quantity's rows for a line through its samples: the first and last rows and every
    row that differs from the one before or after it (so a plateau is drawn flat between its ends and
    a ramp through each sample); ``every_row`` keeps them all.

    >>> t, v = line_rows(np.array([0, 1, 2, 3, 4, 5]), np.array([[9.0], [9.0], [9.0], [8.0], [7.0], [7.0]]))
    >>> t.tolist(), v[:, 0].tolist()
    ([0, 2, 3, 4, 5], [9.0, 9.0, 8.0, 7.0, 7.0])
    """
    n = len(values)
    if n == 0 or every_row:
        return times, values
    differs = np.any(values[1:] != values[:-1], axis=1)
    keep = np.zeros(n, dtype=bool)
    keep[0] = keep[-1] = True
    keep[1:] |= differs
    keep[:-1] |= differs
    return times[keep], values[keep]


def group_rows(trace: TraceTable, names: Sequence[str], every_row: bool = False) -> tuple[np.ndarray, np.ndarray]:
    """The times (int64 ns) and values (rows, len(names)) sent for signals that share a timestamp
    (one group): rows sorted by the time the values became valid, as :func:`step_rows`."""
    table = trace.table
    if not len(table):
        return np.zeros(0, dtype=np.int64), np.zeros((0, len(names)))
    times = trace.signal_times(names[0])
    cols = [trace.names.index(n) + HEAD for n in names]
    values = table[:, cols]
    order = np.argsort(times, kind="stable")
    if not np.all(order[1:] > order[:-1]):
        times, values = times[order], values[order]
    return (line_rows if _is_analog(trace, names) else step_rows)(times, values, every_row)


def _is_analog(trace: TraceTable, names: Sequence[str]) -> bool:
    return all(trace.kinds.get(n) == "analog" for n in names)


def _time_column(t_ns: np.ndarray) -> Any:
    import rerun as rr

    return rr.TimeColumn(TIMELINE, duration=np.asarray(t_ns, dtype=np.int64).astype("timedelta64[ns]"))


def _series_style(rr: Any, names: list[str], color: int | None = None, *, line: bool = False) -> Any:
    """Step lines (``line``: straight lines through the samples of an analog value), never aggregated:
    the viewer would otherwise average the points under one pixel, turning a one-scan pulse into a
    plateau at 0.5 (``AggregationPolicy.Off``, rerun 0.41). The colours are a uint32 array: a plain list of three
    ints would be read as one RGB colour (three analog lines: a crane's X, Y, Z)."""
    return rr.SeriesLines(
        names=names,
        colors=None if color is None else np.full(len(names), color, dtype=np.uint32),
        interpolation_mode="Linear" if line else "StepAfter",
        aggregation_policy="Off",
    )


def _send_signals(rec: Any, trace: TraceTable, every_row: bool) -> None:
    import rerun as rr

    for group, names in signal_groups(trace).items():
        bools = group in BOOL_GROUPS  # one lane (entity) per Bool; the numbers of a group share one
        lanes = [(lane_entity(group, n), [n]) for n in names] if bools else [(GROUPS[group], names)]
        for entity, series in lanes:
            rec.log(entity, _series_style(rr, series, LANE_COLORS.get(group), line=group == "analog"), static=True)
            times, values = group_rows(trace, series, every_row)
            if len(times):
                rec.send_columns(entity, indexes=[_time_column(times)], columns=rr.Scalars.columns(scalars=values))


# -- events ------------------------------------------------------------------------------------


def event_level(event: TraceEvent) -> str:
    """The text-log level of an event."""
    if event.source == "plant":
        if event.kind == "plant fault":
            return "ERROR"
        return "WARN" if event.kind in _PLANT_MISHAPS else "INFO"
    if event.source == "cpu":
        if event.kind in _CPU_ERRORS or "error" in event.kind:
            return "ERROR"
        return "WARN" if event.kind in _CPU_WARNINGS else "INFO"
    if event.source == "scenario":
        return "WARN" if event.kind == "action failed" else "DEBUG"
    return "WARN" if event.source == "wiring" else "INFO"


def event_text(event: TraceEvent) -> str:
    """One line for the text log: ``part entered S1 (p1): speed=0.1``."""
    who = f" {event.subject}" if event.subject else ""
    part = f" ({event.part})" if event.part and event.part != event.subject else ""
    detail = f": {event.detail}" if event.detail else ""
    return f"{event.kind}{who}{part}{detail}"


def _send_events(rec: Any, events: Sequence[TraceEvent]) -> None:
    import rerun as rr

    by_source: dict[str, list[TraceEvent]] = {}
    for e in sorted(events, key=lambda e: e.t_ns):
        by_source.setdefault(e.source or "other", []).append(e)
    for source, evs in by_source.items():
        rec.send_columns(
            f"events/{_segment(source)}",
            indexes=[_time_column(np.array([e.t_ns for e in evs], dtype=np.int64))],
            columns=rr.TextLog.columns(text=[event_text(e) for e in evs], level=[event_level(e) for e in evs]),
        )


# -- geometry ----------------------------------------------------------------------------------


@lru_cache(maxsize=4096)
def _segment(name: str) -> str:
    """A safe entity path segment."""
    out = "".join(c if c.isalnum() or c in "_-" else "_" for c in name.strip())
    return out or "_"


@lru_cache(maxsize=4096)
def _entity(path: str) -> str:
    return "/".join(_segment(p) for p in path.split("/") if p) or "_"


@lru_cache(maxsize=4096)
def _group(path: str) -> str:
    return _segment(path.split("/", 1)[0])


def _flip(points: np.ndarray) -> np.ndarray:
    """Plant coordinates (y up) to rerun's 2D view (y down), as float32."""
    pts = np.asarray(points, dtype=np.float32).reshape(-1, 2).copy()
    pts[:, 1] = 0.0 - pts[:, 1]
    return pts


def _strips_array(strips: list[np.ndarray]) -> Any:
    """The strips as one arrow ``LineStrip2D`` array, built from one flat numpy array (rerun's own
    conversion goes strip by strip, about 20 µs each)."""
    import pyarrow as pa

    dtype = _strip_type()
    offsets = np.zeros(len(strips) + 1, dtype=np.int32)
    np.cumsum([len(s) for s in strips], out=offsets[1:])
    flat = _flip(np.concatenate(strips)) if strips else np.zeros((0, 2), np.float32)
    inner = pa.FixedSizeListArray.from_arrays(pa.array(flat.ravel(), type=pa.float32()), 2)
    array = pa.ListArray.from_arrays(pa.array(offsets), inner.cast(dtype.value_type))
    return array.cast(dtype)


@lru_cache(maxsize=1)
def _strip_type() -> Any:
    import rerun as rr

    return rr.components.LineStrip2DBatch([np.zeros((2, 2), np.float32)]).as_arrow_array().type


class _Shapes:
    """Strips (polygons, lines) and points (circles, labels) of one entity, optionally per frame."""

    def __init__(self) -> None:
        self.strips: list[np.ndarray] = []
        self.strip_colors: list[tuple[int, int, int]] = []
        self.strip_labels: list[str] = []
        self.points: list[np.ndarray] = []
        self.point_radii: list[float] = []
        self.point_colors: list[tuple[int, int, int]] = []
        self.point_labels: list[str] = []
        self.strip_counts: list[int] = []
        self.point_counts: list[int] = []
        self._strips_done = 0
        self._points_done = 0

    def add(self, d: Drawable, text: str) -> None:
        """Add a shape, drawn with ``text`` beside it ("" for none)."""
        pts = np.asarray(d.points, dtype=np.float32).reshape(-1, 2)
        if len(pts) == 0:
            return
        if d.kind in ("polygon", "line"):
            if d.kind == "polygon" and len(pts) > 2:
                pts = np.concatenate([pts, pts[:1]])
            self.strips.append(pts)
            self.strip_colors.append(d.color)
            self.strip_labels.append(text)
        else:
            self.points.append(pts[:1])
            self.point_radii.append(_LABEL_RADIUS if d.kind == "label" else float(d.radius))
            self.point_colors.append(d.color)
            self.point_labels.append(text)

    def close_frame(self) -> None:
        """Mark the end of one frame's shapes."""
        self.strip_counts.append(len(self.strips) - self._strips_done)
        self.point_counts.append(len(self.points) - self._points_done)
        self._strips_done, self._points_done = len(self.strips), len(self.points)

    def strip_fields(self) -> dict[str, Any]:
        fields: dict[str, Any] = {"strips": _strips_array(self.strips), "colors": _colors(self.strip_colors)}
        if any(self.strip_labels):
            fields["labels"] = self.strip_labels
        return fields

    def point_fields(self) -> dict[str, Any]:
        fields: dict[str, Any] = {
            "positions": _flip(np.concatenate(self.points)) if self.points else np.zeros((0, 2), np.float32),
            "radii": np.array(self.point_radii, dtype=np.float32),
            "colors": _colors(self.point_colors),
        }
        if any(self.point_labels):
            fields["labels"] = self.point_labels
        return fields


def _colors(colors: list[tuple[int, int, int]]) -> np.ndarray:
    return np.array(colors, dtype=np.uint8).reshape(-1, 3)


def static_texts(drawables: Sequence[Drawable]) -> tuple[list[str], set[str]]:
    """What the fixed shapes write, so each text is drawn once: the texts per drawable ("" for none)
    and the set of texts written.

    A ``label`` drawable is a text; any other shape's text is a caption, drawn only where no label
    and no earlier shape writes the same (a light barrier's line, its label and its beam all carry
    ``S1``; the label alone is drawn).
    """
    written = {d.text for d in drawables if d.kind == "label" and d.text}
    texts = []
    for d in drawables:
        if d.kind == "label" or (d.text and d.text not in written):
            texts.append(d.text)
            written.add(d.text)
        else:
            texts.append("")
    return texts, written


def _send_static_geometry(rec: Any, drawables: Sequence[Drawable]) -> set[str]:
    """Log the fixed shapes; return the texts they write (moving shapes do not write them again)."""
    import rerun as rr

    texts, written = static_texts(drawables)
    by_path: dict[str, _Shapes] = {}
    for d, text in zip(drawables, texts, strict=True):
        by_path.setdefault(_entity(d.path), _Shapes()).add(d, text)
    for path, shapes in by_path.items():
        entity = f"plant/static/{path}"
        if shapes.strips:
            rec.log(
                entity,
                rr.LineStrips2D(radii=_LINE_RADIUS, draw_order=_STATIC_LINES, **shapes.strip_fields()),
                static=True,
            )
        if shapes.points:
            rec.log(entity, rr.Points2D(draw_order=_STATIC_POINTS, **shapes.point_fields()), static=True)
    return written


def _send_frames(rec: Any, trace: TraceTable, written: set[str]) -> None:
    """Log the geometry frames; a moving shape's caption is left out when a fixed shape writes it."""
    import rerun as rr

    frames = trace.frames
    if not frames:
        return
    groups: dict[str, _Shapes] = {}
    for d in (d for f in frames for d in f.drawables):
        if _group(d.path) not in groups:
            groups[_group(d.path)] = _Shapes()
    for frame in frames:
        for d in frame.drawables:
            groups[_group(d.path)].add(d, "" if d.text in written else d.text)
        for shapes in groups.values():
            shapes.close_frame()
    index = [_time_column(np.array([f.t_ns for f in frames], dtype=np.int64))]
    for group, shapes in groups.items():
        entity = f"plant/moving/{group}"
        if shapes.strips:
            rec.log(entity, rr.LineStrips2D.from_fields(radii=_LINE_RADIUS, draw_order=_MOVING_LINES), static=True)
            columns = rr.LineStrips2D.columns(**shapes.strip_fields()).partition(shapes.strip_counts)
            rec.send_columns(entity, indexes=index, columns=columns)
        if shapes.points:
            rec.log(entity, rr.Points2D.from_fields(draw_order=_MOVING_POINTS), static=True)
            columns = rr.Points2D.columns(**shapes.point_fields()).partition(shapes.point_counts)
            rec.send_columns(entity, indexes=index, columns=columns)


def has_geometry(trace: TraceTable) -> bool:
    """Whether the trace has a plant to draw."""
    return bool(trace.static_drawables or any(f.drawables for f in trace.frames))


def _bounds(trace: TraceTable) -> tuple[float, float, float, float] | None:
    if trace.bounds is not None:
        return tuple(float(v) for v in trace.bounds)  # type: ignore[return-value]
    pts = [np.asarray(d.points, dtype=float).reshape(-1, 2) for d in trace.static_drawables]
    pts += [np.asarray(d.points, dtype=float).reshape(-1, 2) for f in trace.frames[:1] for d in f.drawables]
    if not pts:
        return None
    allp = np.concatenate(pts)
    (x0, y0), (x1, y1) = allp.min(axis=0), allp.max(axis=0)
    return float(x0), float(y0), float(x1), float(y1)


# -- blueprint ---------------------------------------------------------------------------------


def make_blueprint(trace: TraceTable) -> Any:
    """The viewer layout: the machine beside (or, for a wide machine, above) the signals, the events
    and the run's description in tabs."""
    import rerun.blueprint as rrb

    side = rrb.Tabs(rrb.TextLogView(origin="events", name="Events"), rrb.TextDocumentView(origin="meta", name="Run"))
    signals, lanes = signal_panel(trace)
    if has_geometry(trace):
        bounds = _bounds(trace)
        view_kw: dict[str, Any] = {}
        if bounds is not None:
            x0, y0, x1, y1 = bounds
            mx, my = 0.05 * (x1 - x0) + 1.0, 0.05 * (y1 - y0) + 1.0
            view_kw["visual_bounds"] = rrb.VisualBounds2D(x_range=(x0 - mx, x1 + mx), y_range=(-y1 - my, -y0 + my))
        machine = rrb.Spatial2DView(origin="plant", name=f"Machine{_plant_name(trace)}", **view_kw)
        wide = bounds is not None and (bounds[2] - bounds[0]) > 2.0 * (bounds[3] - bounds[1])
        if wide:
            top = rrb.Horizontal(machine, side, column_shares=[3, 1])
            machine_share = max(2.0, MACHINE_SHARE * lanes)
            layout: Any = rrb.Vertical(top, signals, row_shares=[machine_share, lanes]) if signals else top
        else:
            left = rrb.Vertical(machine, side, row_shares=[3, 2])
            layout = rrb.Horizontal(left, signals, column_shares=[1, 1]) if signals else left
    else:
        layout = rrb.Horizontal(signals, side, column_shares=[3, 1]) if signals else side
    return rrb.Blueprint(
        layout,
        rrb.TimePanel(timeline=TIMELINE, state="collapsed"),  # the time bar only: the room goes to the lanes
        rrb.BlueprintPanel(state="collapsed"),
        rrb.SelectionPanel(state="collapsed"),
    )


def signal_panel(trace: TraceTable) -> tuple[Any, float]:
    """The signal lanes and their height in lanes: in one column, or, when more than
    :data:`LANES_PER_COLUMN` would make each too low to read (rerun then cuts off a plot's 0 line
    and time axis), in two: inputs and outputs beside the internal bits and the numbers.
    (None, 0) when the trace has no signals."""
    import rerun.blueprint as rrb

    views, shares = signal_lanes(trace)
    if not views:
        return None, 0.0
    if len(views) <= LANES_PER_COLUMN:
        return rrb.Vertical(*views, row_shares=shares, name="Signals"), sum(shares)
    io = sum(len(signal_groups(trace).get(g, [])) for g in ("inputs", "outputs")) or len(views) // 2
    columns = [rrb.Vertical(*views[:io], row_shares=shares[:io]), rrb.Vertical(*views[io:], row_shares=shares[io:])]
    return rrb.Horizontal(*columns, name="Signals"), max(sum(shares[:io]), sum(shares[io:]))


def signal_lanes(trace: TraceTable) -> tuple[list[Any], list[float]]:
    """The signal views, top to bottom, and their heights: one lane per Bool (inputs, outputs,
    internal; the first lane of a group carries the group's title), then one plot of the numbers and
    one of the plant's analog values, each 2.5 lanes high. All share one time axis, so zooming one zooms all."""
    import rerun.blueprint as rrb

    groups = signal_groups(trace)
    linked = rrb.TimeAxis(link="LinkToGlobal")
    views: list[Any] = []
    shares: list[float] = []
    for group in BOOL_GROUPS:
        for k, name in enumerate(groups.get(group, [])):
            views.append(
                rrb.TimeSeriesView(
                    origin=lane_entity(group, name),
                    name=GROUP_TITLES[group] if k == 0 else name,
                    titlebar=k == 0,
                    axis_x=linked,
                    axis_y=rrb.ScalarAxis(range=(-0.15, 1.15), zoom_lock=True),
                    plot_legend=rrb.PlotLegend("LeftTop"),
                )
            )
            shares.append(1.0 + TITLE_SHARE * (k == 0))
    plots = {"numbers": "numbers" in groups or "number_outputs" in groups, "analog": "analog" in groups}
    for group in (g for g, shown in plots.items() if shown):
        views.append(
            rrb.TimeSeriesView(
                origin=GROUPS[group], name=GROUP_TITLES[group], axis_x=linked, plot_legend=rrb.PlotLegend("LeftTop")
            )
        )
        shares.append(2.5)
    return views, shares


MACHINE_SHARE = 0.4
"""A wide machine's height above the lanes, per lane of signals (at least two lanes)."""
LANES_PER_COLUMN = 8
"""More signal views than this and they are laid out in two columns."""
TITLE_SHARE = 0.45
"""Extra height of a group's first lane, for its title bar (so its plot is as high as the others)."""


def _plant_name(trace: TraceTable) -> str:
    plant = trace.meta.get("plant")
    return f" ({plant})" if plant else ""
