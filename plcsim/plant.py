"""The Plant protocol: what the scheduler, the wiring, scenarios and traces need from a machine model.

A plant knows nothing of PLCs. It has named signals: **sensors** it reports (a light barrier is
``True`` while its beam is interrupted, a button while pressed, a limit switch while actuated) and
**actuators** it obeys (a belt motor, a lamp). The wiring maps them to PLC addresses (NO/NC,
scaling, faults). Units are mm, g and s; time is integer nanoseconds.

Performance contract (the co-simulation budget depends on it): :attr:`Plant.sensors` is a live
dict that :meth:`Plant.step` keeps up to date, so reading it costs a dict lookup; :meth:`Plant.actuate`
is called only when an output changes.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any, Literal, Protocol, runtime_checkable

import numpy as np


@dataclass(frozen=True)
class SignalSpec:
    """One plant signal.

    Attributes:
        name: the plant's name for it (``S1``, ``D1``, ``TLACIDLO``).
        direction: ``sensor`` (plant -> PLC input) or ``actuator`` (PLC output -> plant).
        kind: ``bool`` or ``analog``.
        doc: what it means physically ("light barrier at 40 mm: True while interrupted").
        unit, lo, hi: physical unit and range of an analog signal.
        operator: True for a sensor the operator drives (a button or switch on a panel).
    """

    name: str
    direction: Literal["sensor", "actuator"]
    kind: Literal["bool", "analog"] = "bool"
    doc: str = ""
    unit: str = ""
    lo: float = 0.0
    hi: float = 1.0
    operator: bool = False


@dataclass(frozen=True)
class Station:
    """A named place where an operator can put or take a part (``S1``, ``loading``, ``D3_OS``)."""

    name: str
    x: float
    y: float = 0.0
    doc: str = ""


@dataclass(frozen=True)
class PlantEvent:
    """Something that happened in the plant, stamped with simulated time.

    ``kind`` is one of a small vocabulary checks can rely on: ``part placed``, ``part removed``,
    ``part entered``, ``part left`` (a sensor zone, ``subject`` = the sensor), ``part fell off``,
    ``end stop hit``, ``part jammed``, ``part released``, ``part knocked off``, ``motor jammed``,
    ``interlock violated``, ``button pressed``, ``button released``.
    """

    t_ns: int
    kind: str
    subject: str
    part: str | None = None
    data: Mapping[str, Any] = field(default_factory=dict)


@dataclass(frozen=True)
class Drawable:
    """One shape to draw, in plant coordinates (mm, y up).

    Attributes:
        path: entity path below the plant, e.g. ``belt/D1``, ``parts/p3``, ``beams/S1``.
        kind: ``polygon`` (closed), ``line`` (open polyline), ``circle`` or ``label``.
        points: (N, 2) array of vertices; a circle or label has one point.
        color: RGB 0..255.
        radius: for circles.
        text: label text, or a short caption for the shape.
    """

    path: str
    kind: Literal["polygon", "line", "circle", "label"]
    points: np.ndarray
    color: tuple[int, int, int] = (128, 128, 128)
    radius: float = 0.0
    text: str = ""


@runtime_checkable
class Plant(Protocol):
    """A machine model the CPU can control through the wiring."""

    name: str
    view: Literal["side", "top", "panel"]
    signals: Mapping[str, SignalSpec]
    stations: Mapping[str, Station]
    sensors: dict[str, Any]
    now_ns: int
    events: list[PlantEvent]

    def reset(self, *, seed: int | None = None) -> None:
        """Back to the initial state (no parts, actuators off, time 0)."""

    def actuate(self, name: str, value: Any) -> None:
        """A PLC output changed: apply the new command (from the next step on)."""

    def step(self, dt_ns: int) -> None:
        """Advance the physics by ``dt_ns`` and update :attr:`sensors` and :attr:`events`."""

    def operate(self, name: str, value: Any) -> None:
        """The operator sets a button or switch (a sensor with ``operator=True``)."""

    def place(
        self,
        station: str,
        *,
        part: str | None = None,
        offset_mm: float = 0.0,
        angle_deg: float = 0.0,
        **properties: Any,
    ) -> str:
        """Put a new part at a station (with the given pose error); returns its id."""

    def remove(self, target: str) -> None:
        """Take away a part, by id or by the station it is at."""

    def hold(self, target: str) -> None:
        """Jam a part: it is held in place (a belt slips under it) until :meth:`release`."""

    def release(self, target: str) -> None:
        """Free a held part."""

    def knock_off(self, target: str) -> None:
        """Push a part off the machine (it falls off the belt)."""

    def static_drawables(self) -> list[Drawable]:
        """Shapes that never move (frame, belts, sensor positions), drawn once."""

    def dynamic_drawables(self) -> list[Drawable]:
        """Shapes of the current state (parts, lit beams, lamps, piston rods)."""

    def bounds(self) -> tuple[float, float, float, float]:
        """The area to show: (xmin, ymin, xmax, ymax) in mm."""
