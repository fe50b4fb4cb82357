"""A conveyor belt seen from above: a kinematic body moving at the belt speed that carries the parts on it.

There is no normal force in a top view, so ``surface_velocity`` does nothing; a part on the belt is tied to the
belt's kinematic body by the top view's friction joints instead (pymunk notes §2a), so it rides at the belt speed and
a piston can still push it sideways against that friction. A part that has left the belt's area completely (pushed
off the side, carried off the end) is tied to the table instead and slides to a stop. What tells is not a sensor zone
over the whole area (the collision detection would test every part on the belt against it in every step) but four
thin zones just inside its edges: a part crossing an edge touches the strip there, and once it touches none with its
centre outside the area it has left it, in the same step as it would have left a zone over the whole area. Listed
among a top-view rig's components, the belt carries the parts placed on it by itself (``carrier_at``).
The drive is first order (τ), like the side-view belt.
"""

from __future__ import annotations

import math
from typing import Any

import pymunk

from plants.components import chipmunk, draw
from plants.components.component import Host, zone
from plants.components.sketch import Sketch
from plcsim.plant import Drawable, SignalSpec

EDGE_MM = 2.0  # the width of the sensor strips inside the belt's edges (a part moves far less in a step)


class TopBelt:
    """Belt ``name`` over x0..x1, y0..y1 (mm), forward (+x) at ``speed`` while ``actuator`` is True."""

    EVENTS: frozenset[str] = frozenset()

    def __init__(
        self,
        name: str,
        actuator: str,
        area: tuple[float, float, float, float],
        *,
        speed: float = 50.0,
        tau_s: float = 0.05,
        doc: str = "",
        label_at: tuple[float, float] | None = None,
    ) -> None:
        self.name, self.actuator, self.area = name, actuator, tuple(float(v) for v in area)
        self.label_at = label_at  # where the name is written (default: a caption on the belt)
        self.speed, self.tau_s = float(speed), float(tau_s)
        self.doc = doc or f"belt {name} forward at {speed:g} mm/s while True (τ {tau_s * 1e3:g} ms)"
        self._sketch = Sketch(self._draw)

    def specs(self) -> list[SignalSpec]:
        return [SignalSpec(self.actuator, "actuator", doc=self.doc)]

    def subjects(self) -> set[str]:
        return {self.name}

    def reset(self, host: Host) -> bool:
        self.v = 0.0
        self.target = 0.0
        self.body = pymunk.Body(body_type=pymunk.Body.KINEMATIC)
        x0, y0, x1, y1 = self.area
        host.space.add(self.body)
        self._touching: dict[str, tuple[Any, set[int]]] = {}  # part id -> (part, the edge strips it touches)
        e = min(EDGE_MM, (x1 - x0) / 2, (y1 - y0) / 2)
        strips = ((x0, y0, x1, y0 + e), (x0, y1 - e, x1, y1), (x0, y0, x0 + e, y1), (x1 - e, y0, x1, y1))
        for k, (a, b, c, d) in enumerate(strips):
            zone(host, _Edge(self, k), pymunk.Poly(host.space.static_body, [(a, b), (c, b), (c, d), (a, d)]))
        return False

    def carrier_at(self, x: float, y: float) -> pymunk.Body | None:
        """A part placed on the belt's area rides on the belt (the :class:`Carrier` protocol)."""
        x0, y0, x1, y1 = self.area
        return self.body if x0 <= x <= x1 and y0 <= y <= y1 else None

    def enter(self, host: Any, part: Any) -> None:
        """(The zone protocol: the belt's zones are its edge strips, :class:`_Edge`.)"""

    def leave(self, host: Any, pid: str) -> None:
        """Part ``pid`` was taken out of the rig: it touches no strip any more."""
        self._touching.pop(pid, None)

    def touch(self, part: Any, strip: int) -> None:
        """``part`` touches edge strip ``strip``."""
        self._touching.setdefault(part.id, (part, set()))[1].add(strip)

    def untouch(self, host: Any, pid: str, strip: int) -> None:
        """Part ``pid`` no longer touches edge strip ``strip``; touching none with its centre outside the area, it
        has left the belt: it now lies on the table."""
        entry = self._touching.get(pid)
        if entry is None:
            return
        part, strips = entry
        strips.discard(strip)
        if strips:
            return
        del self._touching[pid]
        p = chipmunk.get_position(part._h)
        x0, y0, x1, y1 = self.area
        if not (x0 <= p.x <= x1 and y0 <= p.y <= y1):
            host.support(pid, host.space.static_body)

    def actuate(self, host: Host, signal: str, value: Any) -> bool:
        self.target = self.speed if value else 0.0
        return self.target != self.v

    def advance(self, host: Host, dt: float) -> bool:
        v = self.target + (self.v - self.target) * math.exp(-dt / self.tau_s)
        settled = abs(v - self.target) < 1e-4
        self.v = self.target if settled else v
        self.body.velocity = (self.v, 0.0)
        return not settled

    def static_drawables(self) -> list[Drawable]:
        x0, y0, x1, y1 = self.area
        belt = draw.polygon(f"belt/{self.name}", draw.rect(x0, y0, x1, y1), draw.BELT, self.name)
        if self.label_at is None:
            return [belt]
        return [belt, draw.label(f"belt/{self.name}/label", *self.label_at, self.name)]

    def dynamic_drawables(self) -> list[Drawable]:
        return self._sketch(self.v == 0.0)

    def _draw(self) -> list[Drawable]:
        if self.v == 0.0:
            return []
        x0, y0, x1, _ = self.area
        xm = 0.5 * (x0 + x1)
        return [draw.arrow(f"belt/{self.name}/direction", xm - 15.0, xm + 15.0, y0 - 6.0, draw.BELT_RUNNING)]


class _Edge:
    """The sensor zone of one edge strip of a belt: the top view's collision callback calls ``enter``/``leave``."""

    def __init__(self, belt: TopBelt, strip: int) -> None:
        self.belt, self.strip = belt, strip

    def enter(self, host: Host, part: Any) -> None:
        self.belt.touch(part, self.strip)

    def leave(self, host: Host, pid: str) -> None:
        self.belt.untouch(host, pid, self.strip)
