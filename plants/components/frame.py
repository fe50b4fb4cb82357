"""The fixed parts of a side-view belt line's frame, as components: an end stop across a belt end and the dead plate
that bridges two belts in series. They have no signals; an end stop reports the parts that hit it."""

from __future__ import annotations

from typing import Any

import pymunk

from plants.components import draw
from plants.components.collide import CT_PLATE, CT_STOP, PLATE_CAT, STOP_CAT
from plants.components.component import Host
from plants.components.workpiece import Part
from plcsim.plant import Drawable, SignalSpec


class _Fixed:
    """No signals, nothing to advance, drawn under the parts."""

    layer = "under"

    def specs(self) -> list[SignalSpec]:
        return []

    def actuate(self, host: Host, signal: str, value: Any) -> bool:
        return False

    def advance(self, host: Host, dt: float) -> bool:
        return False

    def dynamic_drawables(self) -> list[Drawable]:
        return []


class EndStop(_Fixed):
    """A fixed stop across the belt end: parts pile up against it; a contact gives one ``end stop hit`` event."""

    EVENTS = frozenset({"end stop hit"})

    def __init__(
        self,
        name: str,
        x: float,
        top: float,
        *,
        side: str = "downstream",
        height: float = 30.0,
        thickness: float = 5.0,
        friction: float = 0.3,
    ) -> None:
        if side not in ("downstream", "upstream"):
            raise ValueError(f"end stop side must be 'downstream' or 'upstream', not {side!r}")
        self.name = name
        self.x = float(x)  # the face the parts touch
        self.top = float(top)
        self.side = side
        self.height = float(height)
        self.thickness = float(thickness)
        self.friction = float(friction)

    def subjects(self) -> set[str]:
        return {self.name}

    def box(self) -> tuple[float, float, float, float]:
        x0, x1 = (self.x, self.x + self.thickness) if self.side == "downstream" else (self.x - self.thickness, self.x)
        return (x0, self.top - 10.0, x1, self.top + self.height)

    def reset(self, host: Host) -> bool:
        self.attach(host.space)
        return False

    def attach(self, space: pymunk.Space) -> pymunk.Poly:
        x0, y0, x1, y1 = self.box()
        shape = pymunk.Poly(space.static_body, [(x0, y0), (x1, y0), (x1, y1), (x0, y1)])
        shape.friction = self.friction
        shape.collision_type = CT_STOP
        shape.filter = pymunk.ShapeFilter(categories=STOP_CAT)
        shape.owner = self  # read back in the rig's collision callbacks
        space.add(shape)
        return shape

    def enter(self, host: Host, part: Part) -> None:
        """A part touches the stop: one event per contact (its speed then)."""
        if part.at_stop or part.state in ("off", "gone"):
            return
        part.at_stop = True
        host.emit("end stop hit", self.name, part.id, speed=abs(part.body.velocity.x))

    def leave(self, host: Host, part: Part) -> None:
        part.at_stop = False

    def static_drawables(self) -> list[Drawable]:
        bx0, by0, bx1, by1 = self.box()
        return [draw.polygon(f"frame/{self.name}", draw.rect(bx0, by0, bx1, by1), draw.END_STOP, self.name)]


class DeadPlate(_Fixed):
    """A fixed plate that bridges the gap between two belts, 0.5 mm below the belt surface.

    A 30 mm part crosses a 5 mm gap without ever touching it (it is carried by the belts on both sides); the plate is
    there to stop the part tipping into the gap and to be drawn. Level with the belts it would catch the leading
    corner (checked: a level plate stops a part dead at the gap).
    """

    EVENTS: frozenset[str] = frozenset()

    def __init__(
        self, name: str, x0: float, x1: float, top: float, *, drop: float = 0.5, friction: float = 0.1
    ) -> None:
        self.name = name
        self.x0 = float(x0)
        self.x1 = float(x1)
        self.top = float(top) - drop
        self.friction = float(friction)

    def subjects(self) -> set[str]:
        return set()

    def reset(self, host: Host) -> bool:
        self.attach(host.space)
        return False

    def attach(self, space: pymunk.Space) -> pymunk.Segment:
        r = 1.0
        seg = pymunk.Segment(space.static_body, (self.x0 - r, self.top - r), (self.x1 + r, self.top - r), r)
        seg.friction = self.friction
        seg.collision_type = CT_PLATE
        seg.filter = pymunk.ShapeFilter(categories=PLATE_CAT)
        space.add(seg)
        return seg

    def static_drawables(self) -> list[Drawable]:
        return [
            draw.polygon(f"frame/{self.name}", draw.rect(self.x0, self.top - 3.0, self.x1, self.top), draw.DEAD_PLATE)
        ]
