"""A rig drawn as a picture (``plcsim draw RIG -o rig.png``): its layout before a single check is written.

It draws what a recording draws, the plant's :class:`~plcsim.plant.protocol.Drawable` shapes (fixed ones, then the
moving ones at rest after ``reset``), with the recording's rule for texts (:func:`~plcsim.trace.rerun.static_texts`:
each text once), each written as the viewer writes it (centred below its point, on a light box), in plant
coordinates (mm, y up) with a millimetre grid, and adds what a scenario names: the stations, as ``▼ name``.
Like the timing diagrams the figure is a plain matplotlib ``Figure``, not pyplot's.

>>> from plcsim.plant import Drawable, Station, PARTS
>>> import numpy as np
>>> class Belt:
...     name, CAPABILITIES = "BELT", frozenset({PARTS})
...     stations = {"S1": Station("S1", 20.0, 10.0)}
...     def static_drawables(self):
...         return [Drawable("belt/D1", "polygon", np.array([[0, 0], [200, 0], [200, 10], [0, 10.0]]), text="D1")]
...     def dynamic_drawables(self): return []
...     def bounds(self): return (-10.0, -10.0, 210.0, 30.0)
>>> fig = rig_figure(Belt())
>>> sorted(t.get_text() for t in fig.axes[0].texts)
['D1', '▼ S1']
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

import numpy as np

from plcsim.plant.protocol import Drawable, stations_of
from plcsim.trace.rerun import static_texts

STATION_COLOR = "#1971c2"


def rig_figure(plant: Any, *, width_in: float = 10.0) -> Any:
    """The plant at rest, drawn into a new figure (``width_in`` inches wide, the height as the rig's bounds ask)."""
    from matplotlib.figure import Figure

    x0, y0, x1, y1 = (float(v) for v in plant.bounds())
    height = min(max(width_in * (y1 - y0) / max(x1 - x0, 1e-9), 2.5), 2.0 * width_in)
    fig = Figure(figsize=(width_in, height + 0.6), layout="constrained")
    ax = fig.add_subplot()
    shapes = list(plant.static_drawables()) + list(plant.dynamic_drawables())
    texts, _ = static_texts(shapes)
    size = 7.0 if len(shapes) > 30 else 8.0
    for d, text in zip(shapes, texts, strict=True):
        _draw(ax, d, text, size)
    for st in stations_of(plant).values():
        ax.plot([st.x], [st.y], marker="v", color=STATION_COLOR, markersize=7, zorder=7)
        ax.annotate(
            f"▼ {st.name}",
            (st.x, st.y),
            xytext=(5, -12),
            textcoords="offset points",
            color=STATION_COLOR,
            fontsize=size,
            fontweight="bold",
            zorder=7,
        )
    ax.set_xlim(x0, x1)
    ax.set_ylim(y0, y1)
    ax.set_aspect("equal")
    ax.grid(True, linewidth=0.3, alpha=0.5)
    ax.set_xlabel("x (mm)")
    ax.set_ylabel("y (mm)")
    ax.set_title(f"{plant.name} ({getattr(plant, 'view', '?')} view, at rest; ▼ stations)")
    return fig


def save_rig_drawing(plant: Any, path: str | Path, *, dpi: int = 120) -> Path:
    """Write :func:`rig_figure` of ``plant`` as a PNG; returns the path."""
    path = Path(path)
    rig_figure(plant).savefig(path, dpi=dpi)
    return path


def _draw(ax: Any, d: Drawable, text: str, size: float) -> None:
    pts = np.asarray(d.points, dtype=float).reshape(-1, 2)
    rgb = tuple(c / 255.0 for c in d.color)
    if d.kind == "polygon":
        from matplotlib.patches import Polygon

        ax.add_patch(Polygon(pts, closed=True, facecolor=rgb, edgecolor=_darker(rgb), linewidth=0.8, alpha=0.9))
        where = np.concatenate([pts, pts[:1]]).mean(axis=0)  # the recording closes the outline: its first corner twice
    elif d.kind == "line":
        ax.plot(pts[:, 0], pts[:, 1], color=rgb, linewidth=2.0)
        where = pts.mean(axis=0)
    elif d.kind == "circle":
        from matplotlib.patches import Circle

        ax.add_patch(Circle(tuple(pts[0]), max(d.radius, 0.5), facecolor=rgb, edgecolor=_darker(rgb), zorder=3))
        where = pts[0]
    else:
        where = pts[0]
    if text:  # as a recording writes it: centred below its point, on a light box readable on any fill
        ax.annotate(
            text,
            tuple(where),
            xytext=(0, -3),
            textcoords="offset points",
            fontsize=size,
            ha="center",
            va="top",
            zorder=6,
            color="#212529",
            bbox={"boxstyle": "round,pad=0.2", "facecolor": "white", "edgecolor": "none", "alpha": 0.75},
        )


def _darker(rgb: tuple[float, ...]) -> tuple[float, ...]:
    return tuple(0.6 * c for c in rgb)
