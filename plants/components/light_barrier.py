"""A light barrier (through-beam photo sensor) in a side view.

The beam crosses the belt perpendicular to the drawing plane, so in the side view it is a small spot: a sensor
box ``width`` wide (along the travel) and ``height`` high, centred ``x`` along the line and ``y`` above the base.
It is event-driven: pymunk calls ``begin`` when a part starts to overlap the beam and ``separate`` when it stops;
the barrier keeps the parts in the beam in an insertion-ordered dict (an ordered set: it never depends on string
hashing, so event order is the same in every process) and counts both callbacks. The barrier is **interrupted**
while any part overlaps it. The plant reports the physical state (True = interrupted); NO/NC is the wiring's job.

A fault can shift the beam (``dx``, misaligned sensor); the station where an operator puts a part stays where it
was, so the sensor's edges move by ``dx / v``.
"""

from __future__ import annotations

import pymunk

from plants.components.collide import BEAM_CAT, CT_BEAM, PART_CAT


class LightBarrier:
    """One beam. ``x``/``y``: nominal centre of the beam spot (mm); ``dx``: fault shift (mm)."""

    def __init__(
        self, name: str, x: float, y: float, *, width: float = 2.0, height: float = 2.0, doc: str = ""
    ) -> None:
        if width <= 0 or height <= 0:
            raise ValueError(f"light barrier {name}: width and height must be > 0")
        self.name = name
        self.x = float(x)
        self.y = float(y)
        self.width = float(width)
        self.height = float(height)
        self.doc = doc
        self.shape: pymunk.Poly | None = None
        self.reset()

    def reset(self) -> None:
        self.dx = 0.0
        self.parts: dict[str, None] = {}  # part ids in the beam, in the order they entered
        self.begins = 0  # begin callbacks counted (entries)
        self.separates = 0  # separate callbacks counted (exits)
        self.rebuilding: dict[str, None] | None = None  # members before a shift, until the next step re-detects
        self.shape = None

    @property
    def x_actual(self) -> float:
        """Where the beam really is (nominal + fault shift)."""
        return self.x + self.dx

    @property
    def interrupted(self) -> bool:
        return bool(self.parts)

    @property
    def count(self) -> int:
        return len(self.parts)

    def make_shape(self, space: pymunk.Space) -> pymunk.Poly:
        """A static sensor box at the beam's actual position (not yet added to the space)."""
        x, y, hw, hh = self.x_actual, self.y, self.width / 2, self.height / 2
        shape = pymunk.Poly(space.static_body, [(x - hw, y - hh), (x + hw, y - hh), (x + hw, y + hh), (x - hw, y + hh)])
        shape.sensor = True
        shape.collision_type = CT_BEAM
        shape.filter = pymunk.ShapeFilter(categories=BEAM_CAT, mask=PART_CAT)
        shape.barrier = self  # read back in the collision callbacks
        return shape

    def attach(self, space: pymunk.Space) -> pymunk.Poly:
        self.shape = self.make_shape(space)
        space.add(self.shape)
        return self.shape
