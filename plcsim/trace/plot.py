"""Timing diagrams of a :class:`~plcsim.trace.facade.Trace` with matplotlib, for notebooks, reports and failed checks.

One lane per signal, top to bottom in the order given: a Bool as a 0/1 step (shaded while TRUE), a
number as a step scaled to its lane with its values written at each change, a plant's analog value
(kind ``analog``: a press's ram height) as a line scaled to its lane, labelled with its range. The x axis is simulated
time in seconds. Each value is drawn from the moment it became valid: outputs at the end of the scan
that wrote them, inputs and internal tags at the start of the scan (:meth:`Trace.signal_times`).

>>> from plcsim.trace.facade import Trace
>>> tr = Trace(["S1", "D1"], kinds={"S1": "input", "D1": "output"}, types={"S1": "bool", "D1": "bool"})
>>> for k in range(5):
...     tr.add_row(k * 1_000_000, k * 1_000_000 + 400_000, 1, (k >= 1, k >= 2))
>>> fig = timing_diagram(tr, highlight=(2_000_000, 3_000_000, "D1 late"))
>>> [line.get_gid() for line in fig.axes[0].lines if (line.get_gid() or "").startswith("lane:")]
['lane:S1', 'lane:D1']

The figure is a plain :class:`matplotlib.figure.Figure`, not registered with pyplot (nothing is shown,
no GUI backend is needed, nothing accumulates in pyplot's figure list): a notebook shows it when it is
a cell's value, :func:`save_timing_diagram` writes a PNG, and ``ax=`` draws into an axes of your own.
"""

from __future__ import annotations

import io
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import numpy as np

from plcsim.core.literals import to_ns
from plcsim.trace.table import TraceEvent, TraceTable

MAX_DEFAULT_LANES = 24
"""Lanes drawn when no signals are named (inputs first, then outputs, internal bits, numbers)."""
MAX_SCAN_TICKS = 1500
"""More scans than this in view and the scan ticks are left out (they would be a grey wash)."""
MAX_EVENT_LABELS = 30
"""More events than this in view and their lines are drawn without labels."""
MAX_VALUE_LABELS = 16
"""More changes than this in view and a number lane is labelled with its range only."""

LANE = 1.0
HIGH = 0.7  # height of TRUE / of a number's range inside a lane
COLORS = {"input": "#2b8a3e", "output": "#c92a2a", "number": "#6741d9", "internal": "#1864ab", "analog": "#e8590c"}
EVENT_COLORS = {"plant": "#495057", "cpu": "#e03131", "scenario": "#1971c2", "wiring": "#e8590c"}


class TimingDiagram:
    """Mixin giving a figure a PNG representation, so notebooks show it without pyplot."""

    def _repr_png_(self) -> bytes:
        buf = io.BytesIO()
        self.savefig(buf, format="png")  # type: ignore[attr-defined]
        return buf.getvalue()


def _figure_class() -> type:
    from matplotlib.figure import Figure

    return type("TimingDiagramFigure", (TimingDiagram, Figure), {})


def default_signals(trace: TraceTable) -> list[str]:
    """The lanes drawn when none are named: inputs, outputs, internal Bools and the plant's analog values,
    then numbers (at most :data:`MAX_DEFAULT_LANES`)."""

    def rank(name: str) -> int:
        kind, typ = trace.kinds.get(name, "memory"), trace.types.get(name)
        if kind == "analog":
            return 2
        if typ != "bool":
            return 3
        return {"input": 0, "output": 1}.get(kind, 2)

    return sorted(trace.names, key=rank)[:MAX_DEFAULT_LANES]


def _ns(value: str | int | None, what: str) -> int | None:
    return None if value is None else to_ns(value, what)


def steps(trace: TraceTable, name: str, start: int, end: int) -> tuple[np.ndarray, np.ndarray]:
    """The step points of a signal in ``[start, end]``: times (ns) and values, one point at the
    window start (the value valid then, if any), one at each change, and one at ``end``."""
    when = trace.signal_times(name)
    col = trace.column(name).astype(np.float64)
    if len(when) > 1 and np.any(when[1:] < when[:-1]):
        order = np.argsort(when, kind="stable")
        when, col = when[order], col[order]
    k0 = int(np.searchsorted(when, start, side="right")) - 1
    k1 = int(np.searchsorted(when, end, side="right"))
    lo = max(k0, 0)
    if k1 <= lo:
        return np.zeros(0, dtype=np.int64), np.zeros(0)
    t, v = when[lo:k1].copy(), col[lo:k1]
    t[0] = max(int(t[0]), start)
    keep = np.ones(len(v), dtype=bool)
    keep[1:] = v[1:] != v[:-1]
    t, v = t[keep], v[keep]
    return np.append(t, end), np.append(v, v[-1])


def timing_diagram(
    trace: TraceTable,
    signals: Sequence[str] | None = None,
    *,
    start: str | int | None = None,
    end: str | int | None = None,
    scan_ticks: bool = False,
    highlight: tuple[Any, ...] | Sequence[tuple[Any, ...]] | None = None,
    title: str | None = None,
    ax: Any = None,
    events: bool | Sequence[str] = ("plant", "cpu"),
) -> Any:
    """Draw a timing diagram and return its matplotlib Figure.

    Args:
        trace: the run.
        signals: the lanes, top to bottom (default: :func:`default_signals`).
        start, end: the window, as ns or durations such as ``"1.5s"`` (default: the whole run).
        scan_ticks: draw a thin line at the start of every OB1 scan in view.
        highlight: ``(t0_ns, t1_ns)`` or ``(t0_ns, t1_ns, "what went wrong")`` shaded in red
            (``t1_ns`` None: to the end); or a list of them.
        title: the title (default: from the trace's metadata).
        ax: draw into this axes instead of a new figure.
        events: the event sources marked with dotted lines (True: all, False: none).
    """
    names = list(signals) if signals is not None else default_signals(trace)
    for name in names:
        trace.column(name)  # unknown names fail here, with a suggestion
    times, end_times = trace.times, trace.end_times
    t_first = int(times.min()) if len(times) else 0
    t_last = max(int(end_times.max()) if len(end_times) else 0, trace.duration_ns)
    t0 = _ns(start, "start")
    t1 = _ns(end, "end")
    t0 = t_first if t0 is None else t0
    t1 = t_last if t1 is None else t1
    if t1 <= t0:
        t1 = t0 + 1_000_000

    n = len(names)
    if ax is None:
        fig = _figure_class()(figsize=(10.0, 1.1 + 0.42 * max(n, 2)), layout="constrained")
        ax = fig.add_subplot()
    else:
        fig = ax.figure
    sec = 1e-9

    # lanes
    ticks, labels = [], []
    for i, name in enumerate(names):
        base = (n - 1 - i) * LANE
        ticks.append(base + HIGH / 2)
        labels.append(name)
        ax.axhline(base - 0.15, color="#dee2e6", lw=0.6, zorder=0)
        t, v = steps(trace, name, t0, t1)
        if not len(t):
            continue
        x = t * sec
        kind = trace.kinds.get(name, "memory")
        if trace.types.get(name) == "bool":
            color = COLORS.get(kind, COLORS["internal"])
            y = base + HIGH * v
            ax.fill_between(x, base, y, step="post", color=color, alpha=0.18, lw=0, zorder=1)
            ax.plot(x, y, drawstyle="steps-post", color=color, lw=1.4, gid=f"lane:{name}", zorder=3)
        elif kind == "analog":  # sampled every scan: a line through the samples (a plateau's ends are samples)
            vmin, vmax = float(v.min()), float(v.max())
            span = vmax - vmin
            y = base + (HIGH * (v - vmin) / span if span else np.full(len(v), HIGH / 2))
            ax.plot(x, y, color=COLORS["analog"], lw=1.3, gid=f"lane:{name}", zorder=3)
            labels[-1] = f"{name}\n{_fmt(vmin)}..{_fmt(vmax)}"
        else:
            vmin, vmax = float(v.min()), float(v.max())
            span = vmax - vmin
            y = base + (HIGH * (v - vmin) / span if span else np.full(len(v), HIGH / 2))
            ax.plot(x, y, drawstyle="steps-post", color=COLORS["number"], lw=1.3, gid=f"lane:{name}", zorder=3)
            changes = len(v) - 1
            if changes <= MAX_VALUE_LABELS:
                for xk, yk, vk in zip(x[:-1], y[:-1], v[:-1], strict=True):
                    ax.text(
                        xk,
                        yk + 0.04,
                        f" {_fmt(vk)}",
                        fontsize=7,
                        color=COLORS["number"],
                        va="bottom",
                        ha="left",
                        clip_on=True,
                        gid=f"value:{name}",
                    )
            else:
                labels[-1] = f"{name}\n{_fmt(vmin)}..{_fmt(vmax)}"
    ax.set_yticks(ticks, labels)
    ax.tick_params(axis="y", length=0, labelsize=9 if n <= 10 else 8)
    spans = _highlights(highlight)
    shown = _events_in_view(trace.events, events, t0, t1)
    event_rows = 0.48 if shown and len(shown) <= MAX_EVENT_LABELS else 0.0
    note_row = 0.36 if any(len(h) > 2 and h[2] for h in spans) else 0.0
    top = (n - 1) * LANE + HIGH + 0.15 + event_rows + note_row
    ax.set_ylim(-0.3, top)
    ax.set_xlim(t0 * sec, t1 * sec)
    ax.set_xlabel("simulated time [s]")
    ax.grid(axis="x", color="#e9ecef", lw=0.6)
    for side in ("top", "right", "left"):
        ax.spines[side].set_visible(False)

    if scan_ticks:
        scans = times[(trace.tasks == 1) & (times >= t0) & (times <= t1)]
        if len(scans) <= MAX_SCAN_TICKS:
            ax.vlines(scans * sec, -0.3, top - 0.5, colors="#adb5bd", lw=0.4, alpha=0.6, zorder=0, gid="scan_ticks")
        else:
            ax.set_xlabel(f"simulated time [s]   ({len(scans)} scans in view: scan ticks left out; zoom in)")

    _draw_events(ax, shown, top - note_row - 0.02)
    for span in spans:
        _draw_highlight(ax, span, t0, t1, top)

    if title is None:
        title = _title(trace)
    if title:
        ax.set_title(title, fontsize=10, loc="left")
    return fig


def save_timing_diagram(
    trace: TraceTable, path: str | Path, signals: Sequence[str] | None = None, *, dpi: int = 120, **options: Any
) -> Path:
    """Draw a timing diagram (options as :func:`timing_diagram`) and write it as a PNG."""
    path = Path(path)
    fig = timing_diagram(trace, signals, **options)
    fig.savefig(path, dpi=dpi, format="png")
    return path


# -- helpers -----------------------------------------------------------------------------------


def _fmt(value: float) -> str:
    return str(int(value)) if float(value).is_integer() else f"{value:.4g}"


def _title(trace: TraceTable) -> str:
    meta = trace.meta
    parts = [str(meta[k]) for k in ("exercise", "scenario", "program") if meta.get(k) and str(meta[k])[0] != "<"]
    if meta.get("seed") is not None and parts:
        parts.append(f"seed {meta['seed']}")
    return " · ".join(parts)


def _highlights(highlight: Any) -> list[tuple[Any, ...]]:
    if highlight is None:
        return []
    if len(highlight) and isinstance(highlight[0], (tuple, list)):
        return [tuple(h) for h in highlight]
    return [tuple(highlight)]


def _draw_highlight(ax: Any, span: tuple[Any, ...], t0: int, t1: int, top: float) -> None:
    a = _ns(span[0], "highlight start")
    b = _ns(span[1], "highlight end") if len(span) > 1 and span[1] is not None else t1
    text = str(span[2]) if len(span) > 2 and span[2] else ""
    a, b = min(a, b), max(a, b)
    sec = 1e-9
    # keep a one-scan window visible on a long axis
    min_width = (t1 - t0) * 0.004
    if b - a < min_width:
        mid = (a + b) / 2
        a, b = int(mid - min_width / 2), int(mid + min_width / 2)
    ax.axvspan(a * sec, b * sec, color="#ff6b6b", alpha=0.22, lw=0, zorder=0.5, gid="highlight")
    for edge in (a, b):
        ax.axvline(edge * sec, color="#e03131", lw=0.9, zorder=0.6, gid="highlight-edge")
    if text:
        right = (a - t0) > 0.6 * (t1 - t0)
        ax.text(
            (b if right else a) * sec,
            top - 0.03,
            f" {text} ",
            ha="right" if right else "left",
            va="top",
            fontsize=8,
            color="#c92a2a",
            zorder=6,
            bbox={"boxstyle": "round,pad=0.2", "fc": "white", "ec": "#e03131", "lw": 0.6, "alpha": 0.9},
            gid="highlight-text",
        )


def _events_in_view(events: Sequence[TraceEvent], which: bool | Sequence[str], t0: int, t1: int) -> list[TraceEvent]:
    if which is False:
        return []
    return [
        e
        for e in events
        if t0 <= e.t_ns <= t1
        and (which is True or e.source in which)
        and not (e.source == "cpu" and e.kind in ("download", "warning"))
    ]


def _draw_events(ax: Any, shown: Sequence[TraceEvent], top: float) -> None:
    label = len(shown) <= MAX_EVENT_LABELS
    lo, hi = ax.get_xlim()
    near = 0.06 * (hi - lo)  # labels closer than this would overlap: one label for the group
    groups: list[list[TraceEvent]] = []
    for e in shown:
        if groups and e.t_ns * 1e-9 - groups[-1][0].t_ns * 1e-9 < near:
            groups[-1].append(e)
        else:
            groups.append([e])
    for e in shown:
        color = EVENT_COLORS.get(e.source, "#495057")
        ax.axvline(e.t_ns * 1e-9, color=color, ls=":", lw=0.9, zorder=2, gid="event")
    if not label:
        return
    for k, group in enumerate(groups):
        e = group[0]
        color = EVENT_COLORS.get(e.source, "#495057")
        text = f"{e.kind} {e.subject}".strip()[:28] + (f" (+{len(group) - 1})" if len(group) > 1 else "")
        ax.text(
            e.t_ns * 1e-9,
            top - 0.24 * (k % 2),
            f" {text}",
            fontsize=6.5,
            color=color,
            ha="left",
            va="top",
            zorder=5,
            clip_on=True,
            gid="event-label",
        )
