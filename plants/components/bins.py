"""Bins (magazines) beside a machine: zones that record every part that lands in them.

A bin is a static sensor rectangle; a part that reaches it is **in** the bin: ``part in bin`` (subject: the
bin, data: the part's properties the rig declares worth grading, ``report=``: by default ``colour`` and
``colour_raw``; a rig whose parts are ``bad=True`` reports ``("bad",)``), once per part. The rig then takes the part
out of the physics (it lies in the bin) with :meth:`Bins.landed`'s answer. ``contents`` keeps what each bin holds,
in order, for the checks and the drawing.

>>> from plants.components.component import Bench
>>> b = Bins({"bin1": (0, 0, 50, 40), "unsorted": (60, 0, 100, 40)}); host = Bench(); _ = b.reset(host)
>>> b.which(25.0, 20.0), b.which(55.0, 20.0)
('bin1', None)
>>> b.landed(host, "bin1", "p1", {"colour": 2}); b.contents, [(e.kind, e.subject, e.data) for e in host.events]
({'bin1': ['p1'], 'unsorted': []}, [('part in bin', 'bin1', {'colour': 2})])
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping
from typing import Any

import pymunk

from plants.components import draw
from plants.components.component import Host, zone
from plants.components.sketch import Sketch
from plcsim.plant import Drawable, SignalSpec

GRADED = ("colour", "colour_raw")


class Bins:
    """Named bins, each an axis-aligned rectangle (x0, y0, x1, y1) in mm; ``report``: the part properties their
    ``part in bin`` event carries (what ``event_data("part in bin", key)`` can grade)."""

    EVENTS = frozenset({"part in bin"})

    def __init__(
        self,
        bins: Mapping[str, tuple[float, float, float, float]],
        *,
        name: str = "bins",
        report: Iterable[str] = GRADED,
        label_at: Mapping[str, tuple[float, float]] | None = None,
    ) -> None:
        self.name = name
        self.report = tuple(report)
        self.bins = {k: tuple(float(v) for v in box) for k, box in bins.items()}
        # where each bin's "name: count" is written: given, or low in the bin (parts land near its top)
        at = dict(label_at or {})
        self.label_at = {k: at.get(k, (0.5 * (x0 + x1), y0 + 17.0)) for k, (x0, y0, x1, y1) in self.bins.items()}
        self._sketch = Sketch(self._draw)

    def specs(self) -> list[SignalSpec]:
        return []

    def subjects(self) -> set[str]:
        return set(self.bins)

    def reset(self, host: Host) -> bool:
        self.contents: dict[str, list[str]] = {k: [] for k in self.bins}
        if host.space is not None:  # in a space: each bin is a sensor zone; a part touching it has landed there
            for k, (x0, y0, x1, y1) in self.bins.items():
                zone(
                    host, _Zone(self, k), pymunk.Poly(host.space.static_body, [(x0, y0), (x1, y0), (x1, y1), (x0, y1)])
                )
        return False

    def which(self, x: float, y: float) -> str | None:
        """The bin whose area holds (x, y), if any."""
        for k, (x0, y0, x1, y1) in self.bins.items():
            if x0 <= x <= x1 and y0 <= y <= y1:
                return k
        return None

    def landed(self, host: Host, bin_name: str, pid: str, props: Mapping[str, Any]) -> None:
        """Record that part ``pid`` (with these properties) lies in ``bin_name`` (once per part)."""
        if any(pid in parts for parts in self.contents.values()):
            return
        self.contents[bin_name].append(pid)
        host.emit("part in bin", bin_name, pid, **{k: props[k] for k in self.report if k in props})

    def actuate(self, host: Host, signal: str, value: Any) -> bool:
        return False

    def advance(self, host: Host, dt: float) -> bool:
        return False

    def static_drawables(self) -> list[Drawable]:
        return [draw.polygon(f"bins/{k}", draw.rect(*box), (200, 205, 215)) for k, box in self.bins.items()]

    def dynamic_drawables(self) -> list[Drawable]:
        return self._sketch(tuple(map(len, self.contents.values())))

    def _draw(self) -> list[Drawable]:
        return [draw.label(f"bins/{k}/count", *self.label_at[k], f"{k}: {len(self.contents[k])}") for k in self.bins]


class _Zone:
    """The sensor zone of one bin: the top view's collision callback calls ``enter``/``leave``."""

    def __init__(self, bins: Bins, name: str) -> None:
        self.bins, self.name = bins, name

    def enter(self, host: Host, part: Any) -> None:
        self.bins.landed(host, self.name, part.id, part.props)

    def leave(self, host: Host, pid: str) -> None:
        """A part stays recorded where it landed."""
