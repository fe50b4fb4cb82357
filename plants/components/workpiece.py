"""The standard workpiece: a block 30 mm (along the travel) × 30 mm (across) × 20 mm (high), 12 g.

In a side view the block is a 30 × 20 mm box (a pymunk Poly on a dynamic body, mass in kg: the notes' units are
mm/kg/s, so gravity is 9810 mm/s² and 12 g is 0.012). Its friction is 1.0, so a contact's μ is the other shape's
friction (pymunk multiplies the two): belt 0.6, end stop 0.3. The pose error of a placement (offset, angle) is
given by the caller (the scenario draws it from its own seeded generator); the part itself is never random.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np
import pymunk

from plants.components import chipmunk, draw
from plants.components.collide import CT_PART, FALL_CAT, OFF_CAT, PART_CAT
from plcsim.plant import Drawable


@dataclass(frozen=True)
class WorkpieceSpec:
    """Size (mm), mass (g) and friction of a block-shaped workpiece."""

    length: float = 30.0
    depth: float = 30.0
    height: float = 20.0
    mass_g: float = 12.0
    friction: float = 1.0

    def rest_height(self, angle_rad: float) -> float:
        """Height of the centre above the support when the block, turned by ``angle_rad``, touches it with a corner."""
        c, s = abs(math.cos(angle_rad)), abs(math.sin(angle_rad))
        return 0.5 * (self.length * s + self.height * c)


STANDARD = WorkpieceSpec()


@dataclass(eq=False)
class Part:
    """One workpiece in a plant.

    ``state``: ``on`` (on the machine, free), ``held`` (jammed by a pin joint), ``off`` (pushed off the machine,
    falling), ``gone`` (removed from the plant).
    """

    id: str
    spec: WorkpieceSpec
    body: pymunk.Body
    shape: pymunk.Poly
    placed_ns: int
    props: dict[str, Any] = field(default_factory=dict)
    state: str = "on"
    joints: tuple = ()
    at_stop: bool = False  # touching an end stop (debounces the "end stop hit" event)
    drawn: tuple = ()  # (pose, colour, drawable) of the last drawing, reused while the part rests

    def __post_init__(self) -> None:
        self._h = chipmunk.handle(self.body)  # the pose is read at every frame: straight from Chipmunk

    @classmethod
    def create(
        cls, part_id: str, spec: WorkpieceSpec, x: float, y: float, angle_rad: float, now_ns: int, props: dict
    ) -> Part:
        mass = spec.mass_g / 1000.0
        body = pymunk.Body(mass, pymunk.moment_for_box(mass, (spec.length, spec.height)))
        body.position = (x, y)
        body.angle = angle_rad
        shape = pymunk.Poly.create_box(body, (spec.length, spec.height))
        shape.friction = spec.friction
        shape.collision_type = CT_PART
        shape.filter = pymunk.ShapeFilter(categories=PART_CAT)
        part = cls(part_id, spec, body, shape, now_ns, dict(props))
        shape.part = part  # read back in the collision callbacks
        return part

    def push_off(self) -> None:
        """Make the part fall through everything but the fall zone (it has been pushed off sideways)."""
        self.state = "off"
        self.shape.filter = pymunk.ShapeFilter(categories=OFF_CAT, mask=FALL_CAT)

    @property
    def x(self) -> float:
        return chipmunk.get_position(self._h).x

    def pose(self) -> tuple[float, float, float]:
        """(x, y, angle in rad) of the centre."""
        p = chipmunk.get_position(self._h)
        return (p.x, p.y, chipmunk.get_angle(self._h))

    def outline(self, pose: tuple[float, float, float] | None = None) -> np.ndarray:
        """The four corners in world coordinates, (4, 2) (at ``pose``, default: where the part is)."""
        x, y, a = self.pose() if pose is None else pose
        return draw.box(x, y, a, self.spec.length / 2, self.spec.height / 2)

    def drawable(self, color: tuple[int, int, int]) -> Drawable:
        """The part's outline as drawn; the same drawable (they are frozen) while it rests in one pose."""
        pose = self.pose()
        last = self.drawn
        if last and last[0] == pose and last[1] == color:
            return last[2]
        d = Drawable(f"parts/{self.id}", "polygon", self.outline(pose), color, text=self.id)
        self.drawn = (pose, color, d)
        return d
