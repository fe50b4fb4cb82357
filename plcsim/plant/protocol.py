"""The Plant protocol: what the scheduler, the wiring, scenarios and traces need from a machine model.

A plant knows nothing of PLCs. It has named signals: **sensors** it reports (a light barrier is
``True`` while its beam is interrupted, a button while pressed, a limit switch while actuated) and
**actuators** it obeys (a belt motor, a lamp, a piston valve). The wiring maps them to PLC addresses
(NO/NC, scaling, faults). Units are mm, g and s; time is integer nanoseconds.

The **core** (:class:`Plant`) is what every machine has, a press or a crane as much as a belt line:
signals, reset, actuate, step, events and drawing. Everything else is an optional **capability**
the plant *declares* in ``CAPABILITIES`` (a frozenset of the names below), never found by probing
for methods; :func:`capable` reads the declaration and :func:`plcsim.plant.check.check_plant` checks it is kept:

* :data:`PARTS` — ``stations``, ``place(station, ...)``, ``remove(target)`` (:class:`HandlesParts`);
* :data:`PART_FAULTS` — ``hold``, ``release``, ``knock_off`` on a part (:class:`PartFaults`; a belt line);
* :data:`OPERATOR` — ``operate(name, value)`` for its buttons and switches (:class:`Operated`);
* :data:`QUIESCENCE` — ``quiescent()``: True when a step would only advance the clock, so any number
  of steps may be taken at once (the simulator then skips an idle machine's steps);
* :data:`SENSOR_SHIFT` — ``shift_sensor(name, dx_mm)``; :data:`MOTOR_JAM` — ``jam_motor(name, jammed)``;
* :data:`OBSERVABLES` — ``observables() -> dict[str, float]``: analog values worth tracing. Those the
  trace records in every row are named in ``TRACED_OBSERVABLES`` (optional; a press's ram height), read
  together by ``sample_observables()`` (a tuple in that order, cheap: it runs once per scan); the trace
  calls their columns ``plant:<name>`` (kind ``analog``; :func:`traced_observables`).

A plant declares its **event vocabulary**: ``EVENTS`` (every kind it can emit) and
``event_subjects()`` (every name its events can be about, a part's id aside). An exercise whose check
or scenario waits for an event its rig never emits is refused when it is loaded.

A plant that handles parts declares the **properties** a scenario may give a part it places (``place("p1",
at="OS1", colour=2)``) in ``PART_PROPERTIES``, a mapping of each name to what it means (none if it declares none):
a name outside it is refused when the scenario is loaded, or when a live session would record it.

A rig may bring its own **scenario verbs** (``set_colour``, ``jam_piston``): ``VERBS`` maps each name
to a :class:`plcsim.plant.verbs.RigVerb`, which builds the action and names the plant method that
carries it out, so that adding one needs no edit in ``plcsim``.

Performance contract (the co-simulation budget depends on it): :attr:`Plant.sensors` is a live
dict that :meth:`Plant.step` keeps up to date, so reading it costs a dict lookup; :meth:`Plant.actuate`
is called only when an output changes.
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any, Literal, Protocol, runtime_checkable

import numpy as np

from plcsim.plant.verbs import RigVerb


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
    ``interlock violated``, ``button pressed``, ``button released``; the component rigs add ``axis stalled``,
    ``piston extended``, ``piston retracted``, ``piston jammed``, ``compressor failed``, ``part in bin`` and
    ``alignment measured`` (``data`` carries what a check grades: ``event_data(kind, key)``). A plant declares
    the kinds it can emit as a class attribute ``EVENTS`` (a set of strings) and the subjects they can name (a part's id
    aside) with a method ``event_subjects()``; an exercise then refuses, when it is loaded, a check or
    trigger waiting for an event the plant never emits, or for one about a name it does not have.
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


PARTS = "parts"
"""Capability: ``stations``, ``place`` and ``remove`` (an operator puts parts in and takes them out)."""
PART_FAULTS = "part faults"
"""Capability: ``hold``, ``release`` and ``knock_off`` (a part jammed on a belt, or pushed off it)."""
OPERATOR = "operator"
"""Capability: ``operate`` (buttons and switches: sensors with ``operator=True``)."""
QUIESCENCE = "quiescence"
"""Capability: ``quiescent()``, True when a step would only advance the clock."""
SENSOR_SHIFT = "sensor shift"
"""Capability: ``shift_sensor(name, dx_mm)``, a sensor mounted off its place (a fault)."""
MOTOR_JAM = "motor jam"
"""Capability: ``jam_motor(name, jammed)``, a blocked drive (a fault)."""
OBSERVABLES = "observables"
"""Capability: ``observables()``, analog values worth tracing that are not signals."""

CAPABILITY_MEMBERS: dict[str, tuple[str, ...]] = {
    PARTS: ("stations", "place", "remove"),
    PART_FAULTS: ("hold", "release", "knock_off"),
    OPERATOR: ("operate",),
    QUIESCENCE: ("quiescent",),
    SENSOR_SHIFT: ("shift_sensor",),
    MOTOR_JAM: ("jam_motor",),
    OBSERVABLES: ("observables",),
}
"""The members each capability stands for (what a plant declaring it must have)."""


@runtime_checkable
class Plant(Protocol):
    """The core every machine model has; see the module docstring for the optional capabilities."""

    name: str
    view: Literal["side", "top", "panel"]
    signals: Mapping[str, SignalSpec]
    sensors: dict[str, Any]
    now_ns: int
    events: list[PlantEvent]
    EVENTS: frozenset[str] | set[str]
    CAPABILITIES: frozenset[str]
    VERBS: Mapping[str, RigVerb]

    def reset(self, *, seed: int | None = None) -> None:
        """Back to the initial state (no parts, actuators off, time 0)."""

    def actuate(self, name: str, value: Any) -> None:
        """A PLC output changed: apply the new command (from the next step on)."""

    def step(self, dt_ns: int) -> None:
        """Advance the physics by ``dt_ns`` and update :attr:`sensors` and :attr:`events`."""

    def event_subjects(self) -> set[str]:
        """Every name its events can be about (a sensor, a station, a piston), a part's id aside."""

    def static_drawables(self) -> list[Drawable]:
        """Shapes that never move (frame, belts, sensor positions), drawn once."""

    def dynamic_drawables(self) -> list[Drawable]:
        """Shapes of the current state (parts, lit beams, lamps, piston rods)."""

    def bounds(self) -> tuple[float, float, float, float]:
        """The area to show: (xmin, ymin, xmax, ymax) in mm."""


class HandlesParts(Protocol):
    """Capability :data:`PARTS`: an operator puts parts at named stations and takes them away."""

    stations: Mapping[str, Station]

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


class PartFaults(Protocol):
    """Capability :data:`PART_FAULTS`: a part jammed where it is, freed, or pushed off the machine."""

    def hold(self, target: str) -> None:
        """Jam a part: it is held in place (a belt slips under it) until :meth:`release`."""

    def release(self, target: str) -> None:
        """Free a held part."""

    def knock_off(self, target: str) -> None:
        """Push a part off the machine (it falls off the belt)."""


class Operated(Protocol):
    """Capability :data:`OPERATOR`: buttons and switches the operator sets."""

    def operate(self, name: str, value: Any) -> None:
        """The operator sets a button or switch (a sensor with ``operator=True``)."""


def missing_members(obj: Any, protocol: type) -> list[str]:
    """The members of ``protocol`` (a ``Protocol`` class) that ``obj`` lacks, by name, in declaration order.

    >>> class Conveyor:
    ...     name = "belt"
    >>> missing_members(Conveyor(), Plant)[:3]
    ['view', 'signals', 'sensors']
    """
    wanted = [m for m in getattr(protocol, "__annotations__", {})]
    wanted += [m for m, v in vars(protocol).items() if callable(v) and not m.startswith("_")]
    return [m for m in dict.fromkeys(wanted) if not hasattr(obj, m)]


def capable(plant: Any, capability: str) -> bool:
    """Whether ``plant`` declares ``capability`` (False for no plant).

    >>> class Press:
    ...     CAPABILITIES = frozenset({QUIESCENCE})
    >>> capable(Press(), QUIESCENCE), capable(Press(), PARTS), capable(None, PARTS)
    (True, False, False)
    """
    return plant is not None and capability in plant.CAPABILITIES


def stations_of(plant: Any) -> dict[str, Station]:
    """The plant's stations (none if it does not handle parts)."""
    return dict(plant.stations) if capable(plant, PARTS) else {}


def rig_verbs(plant: Any) -> Mapping[str, RigVerb]:
    """The scenario verbs the plant brings (none for no plant)."""
    return {} if plant is None else plant.VERBS


def traced_observables(plant: Any) -> tuple[list[str], Any] | None:
    """The trace columns of the plant's ``TRACED_OBSERVABLES`` and the function sampling them (None: none).

    >>> class Press:
    ...     CAPABILITIES = frozenset({OBSERVABLES})
    ...     TRACED_OBSERVABLES = ("M2.z",)
    ...     def sample_observables(self): return (105.5,)
    >>> names, sample = traced_observables(Press())
    >>> names, sample()
    (['plant:M2.z'], (105.5,))
    """
    names = getattr(plant, "TRACED_OBSERVABLES", ()) if capable(plant, OBSERVABLES) else ()
    if not names:
        return None
    return [f"plant:{n}" for n in names], plant.sample_observables
