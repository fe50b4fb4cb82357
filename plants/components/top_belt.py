"""A conveyor belt seen from above: a kinematic body moving at the belt speed that carries the parts on it.

There is no normal force in a top view, so ``surface_velocity`` does nothing; a part on the belt is tied to the
belt's kinematic body by the top view's friction joints instead (pymunk notes §2a), so it rides at the belt speed and
a piston can still push it sideways against that friction. The belt area is a sensor zone: a part that has left it
completely (pushed off the side, carried off the end) is tied to the table instead and slides to a stop. Listed among
a top-view rig's components, the belt carries the parts placed on it by itself (``carrier_at``).
The drive is first order (τ), like the side-view belt.
"""

from __future__ import annotations

import math
from typing import Any

import pymunk

from plants.components import draw
from plants.components.component import Host, zone
from plants.components.sketch import Sketch
from plcsim.plant import Drawable, SignalSpec


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
        zone(host, self, pymunk.Poly(host.space.static_body, [(x0, y0), (x1, y0), (x1, y1), (x0, y1)]))
        return False

    def carrier_at(self, x: float, y: float) -> pymunk.Body | None:
        """A part placed on the belt's area rides on the belt (the :class:`Carrier` protocol)."""
        x0, y0, x1, y1 = self.area
        return self.body if x0 <= x <= x1 and y0 <= y <= y1 else None

    def enter(self, host: Any, part: Any) -> None:
        """A part touches the belt area (it rides on the belt once it is placed there)."""

    def leave(self, host: Any, pid: str) -> None:
        """The part has left the belt area: it now lies on the table."""
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
