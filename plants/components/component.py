"""The component protocol: one piece of a rig (a piston, an axis, a sensor, a compressor) in one small interface.

A rig is a set of components on a base (``SideViewPlant``, ``TopViewPlant``) that owns the pymunk space, the parts
and the clock. Each component brings its own signals, state, events and drawing; the base adds them up, routes each
actuator command to the component that owns it, and steps only the components that are **busy** (a piston moving, a
pressure building). Adding a component kind means one new file with a class that has these members, and the rig that
uses it; the base needs no change.

* ``name``; ``EVENTS``: the kinds of event it can emit; ``subjects()``: the names its events are about.
* ``specs()``: its signals (:class:`~plcsim.plant.SignalSpec`, sensors and actuators, unique in the rig).
* ``reset(host)``: back to the initial state in a fresh space (``host.space``): add its bodies and shapes, write
  its sensors into ``host.sensors``. Returns True if it is busy from the start.
* ``actuate(host, signal, value)``: one of its actuators changed (the PLC output or the rig's own logic); returns
  True if it now has to be advanced.
* ``advance(host, dt)``: one step of ``dt`` seconds, called *before* the physics step while the component is busy
  (``host.now_ns`` is already the step's end): move, update its sensors in ``host.sensors``, emit events with
  ``host.emit``. Returns False once it has settled (it is then not called again until ``actuate`` or ``host.wake``).
* ``static_drawables()``, ``dynamic_drawables()``: its shapes (:class:`~plcsim.plant.Drawable`).

What a component sees of its rig is the :class:`Host`.

Two roles a top-view component may take on besides (:mod:`plants.components.top_view` relies on them):

* a :class:`ZoneSensor` owns sensor shapes (made with :func:`zone`): the rig calls its ``enter(host, part)`` when a
  part starts to touch one and ``leave(host, part_id)`` when it has left it (a light barrier, a bin, a belt's area);
* a :class:`Carrier` carries the parts that lie on it: ``carrier_at(x, y)`` is the body a part placed at (x, y)
  rests on (a belt's), or None. The rig ties a placed part to the first carrier that claims it, else to the table.
"""

from __future__ import annotations

from collections.abc import Iterable
from typing import Any, Protocol, runtime_checkable

import numpy as np
import pymunk

from plcsim.plant import Drawable, PlantEvent, SignalSpec, missing_members


class Host(Protocol):
    """What a component may use of the rig it is part of."""

    name: str
    space: pymunk.Space
    sensors: dict[str, Any]
    events: list[PlantEvent]
    now_ns: int
    rng: np.random.Generator

    def emit(self, kind: str, subject: str, part: str | None = None, **data: Any) -> None:
        """Record a plant event at the current time (and let the rig react to it)."""

    def wake(self, component: Component) -> None:
        """Advance ``component`` from the next step on (a part arrived in its zone, a supply changed)."""

    def defer(self, component: Any) -> None:
        """Call ``component.commit(host)`` at the start of the next step, before the clock advances (the commands
        of one scan taken together); ``commit`` returns True if the component now has to be advanced."""

    def after_step(self, component: Any) -> None:
        """Call ``component.settle(host)`` after the next physics step (a moved sensor re-detected its parts)."""


@runtime_checkable
class Component(Protocol):
    """One piece of a rig; see the module docstring."""

    name: str
    EVENTS: frozenset[str]

    def specs(self) -> list[SignalSpec]: ...

    def subjects(self) -> set[str]: ...

    def reset(self, host: Host) -> bool: ...

    def actuate(self, host: Host, signal: str, value: Any) -> bool: ...

    def advance(self, host: Host, dt: float) -> bool: ...

    def static_drawables(self) -> list[Drawable]: ...

    def dynamic_drawables(self) -> list[Drawable]: ...


@runtime_checkable
class ZoneSensor(Protocol):
    """The owner of a sensor zone (:func:`zone`): told when a part enters and leaves it."""

    def enter(self, host: Host, part: Any) -> None:
        """A part (with ``id`` and ``props``) starts to touch the zone (called inside a physics step)."""

    def leave(self, host: Host, pid: str) -> None:
        """Part ``pid`` no longer touches the zone (or was removed from the rig)."""


@runtime_checkable
class Carrier(Protocol):
    """A component parts ride on (a belt seen from above)."""

    def carrier_at(self, x: float, y: float) -> pymunk.Body | None:
        """The body a part placed at (x, y) rests on, or None if (x, y) is not on this component."""


def zone(host: Host, owner: ZoneSensor, shape: pymunk.Shape) -> pymunk.Shape:
    """Make ``shape`` a sensor zone of ``owner`` in the host's space: parts do not collide with it, and the top view
    calls ``owner.enter``/``owner.leave`` as they touch it and leave it. Refuses an owner that cannot be told.

    >>> z = zone(Bench(space=pymunk.Space()), object(), pymunk.Circle(None, 3.0))
    Traceback (most recent call last):
    TypeError: object lacks `enter`, `leave` of the zone-sensor protocol (plants.components.component.ZoneSensor)
    """
    lacking = missing_members(owner, ZoneSensor)
    if lacking:
        raise TypeError(
            f"{_named(owner)} lacks {', '.join(f'`{m}`' for m in lacking)} of the zone-sensor protocol "
            f"(plants.components.component.ZoneSensor)"
        )
    from plants.components.collide import BEAM_CAT, CT_BEAM, PART_CAT

    shape.sensor = True
    shape.collision_type = CT_BEAM
    shape.filter = pymunk.ShapeFilter(categories=BEAM_CAT, mask=PART_CAT)
    shape.owner = owner
    host.space.add(shape)
    return shape


def _named(obj: Any) -> str:
    """A component as an error names it: its class, and its name if it has one."""
    name = getattr(obj, "name", None)
    return f"{type(obj).__name__} {name!r}" if isinstance(name, str) else type(obj).__name__


class Assembly:
    """The components of one rig and their bookkeeping: signals, actuator routing, the busy list, events, drawing.

    >>> from plants.components.axis import Axis
    >>> a = Assembly([Axis("RAM", 0.0, 30.0, speed=25.0, plus="DOLE", minus="HORE")])
    >>> [s.name for s in a.specs()], sorted(a.events)
    (['DOLE', 'HORE'], ['axis stalled', 'interlock violated', 'motor jammed'])
    """

    def __init__(self, components: Iterable[Component]) -> None:
        self.components = list(components)
        self.owner: dict[str, Component] = {}
        for c in self.components:
            lacking = missing_members(c, Component)
            if lacking:
                raise TypeError(
                    f"{_named(c)} lacks {', '.join(f'`{m}`' for m in lacking)} of the component protocol "
                    f"(plants.components.component.Component)"
                )
            for spec in c.specs():
                if spec.name in self.owner:
                    raise ValueError(f"signal {spec.name} belongs to both {self.owner[spec.name].name} and {c.name}")
                self.owner[spec.name] = c
        self.busy: list[Component] = []

    def specs(self) -> list[SignalSpec]:
        return [s for c in self.components for s in c.specs()]

    @property
    def events(self) -> frozenset[str]:
        """Every kind of event the components can emit."""
        return frozenset().union(*(c.EVENTS for c in self.components))

    def subjects(self) -> set[str]:
        return set().union(*(c.subjects() for c in self.components))

    def reset(self, host: Host) -> None:
        self.busy = [c for c in self.components if c.reset(host)]

    def owns(self, signal: str) -> bool:
        return signal in self.owner

    def actuate(self, host: Host, signal: str, value: Any) -> None:
        c = self.owner[signal]
        if c.actuate(host, signal, value):
            self.wake(c)

    def wake(self, component: Component) -> None:
        if component not in self.busy:
            self.busy.append(component)

    def advance(self, host: Host, dt: float) -> None:
        """One step of every busy component, in the order they were woken; the settled ones leave the list. A
        component woken during the step (by another one's advance, or after its own in this step) stays on it or
        joins it at the end: it advances in the next step, as :meth:`Host.wake` promises."""
        busy = self.busy
        self.busy = woken = []  # wake() appends here during the step
        if len(busy) == 1:  # the common case (a ram moving, a belt settling): the list is kept while it stays busy
            kept = busy if busy[0].advance(host, dt) else []
        else:
            kept = [c for c in busy if c.advance(host, dt)]
        if woken:
            kept += [c for c in woken if c not in kept]
        self.busy = kept

    def has(self, name: str) -> bool:
        """Whether ``name`` is a component or one of their signals."""
        return name in self.owner or any(c.name == name for c in self.components)

    def find(self, name: str) -> Component:
        """The component named ``name``, or the one owning the signal ``name``."""
        for c in self.components:
            if c.name == name:
                return c
        if name in self.owner:
            return self.owner[name]
        raise KeyError(f"no component or signal {name!r}")

    def jam(self, host: Host, name: str, jammed: bool) -> None:
        """Fault: the drive of the component ``name`` (or owning that signal) is blocked, if it has one."""
        c = self.find(name)
        if not hasattr(c, "jam"):
            raise KeyError(f"{c.name} has no drive to jam")
        if c.jam(host, jammed):
            self.wake(c)

    def shift(self, host: Host, sensor: str, dx: float) -> None:
        """Fault: the sensor ``sensor`` of a component is mounted ``dx`` mm off its place, if it can be."""
        c = self.owner[sensor]
        if not hasattr(c, "shift_cam"):
            raise KeyError(f"{c.name} cannot shift its sensor {sensor}")
        c.shift_cam(sensor, dx)
        self.wake(c)

    def static_drawables(self) -> list[Drawable]:
        return [d for c in self.components for d in c.static_drawables()]

    def dynamic_drawables(self) -> list[Drawable]:
        return [d for c in self.components for d in c.dynamic_drawables()]


class Bench:
    """A minimal :class:`~plants.components.component.Host` to try a component alone (no space, no parts).

    ``step(component)`` advances the clock by ``dt_ns`` and the component by one step.
    """

    name = "bench"

    def __init__(self, dt_ns: int = 1_000_000, seed: int = 0, *, space: pymunk.Space | None = None) -> None:
        self.dt_ns = dt_ns
        self.space: Any = space
        self.sensors: dict[str, Any] = {}
        self.events: list[PlantEvent] = []
        self.now_ns = 0
        self.rng = np.random.default_rng(seed)
        self.woken: list[Any] = []
        self.deferred: list[Any] = []

    def emit(self, kind: str, subject: str, part: str | None = None, **data: Any) -> None:
        self.events.append(PlantEvent(self.now_ns, kind, subject, part, data))

    def wake(self, component: Any) -> None:
        self.woken.append(component)

    def defer(self, component: Any) -> None:
        if component not in self.deferred:
            self.deferred.append(component)

    def after_step(self, component: Any) -> None:
        component.settle(self)

    def step(self, *components: Any) -> None:
        """Commit the deferred commands, advance the clock by ``dt_ns`` and ``components`` by one step."""
        deferred, self.deferred = self.deferred, []
        for c in deferred:
            c.commit(self)
        self.now_ns += self.dt_ns
        for c in components:
            c.advance(self, self.dt_ns / 1e9)
