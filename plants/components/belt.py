"""A side-view conveyor belt: a static segment whose ``surface_velocity`` is the belt speed.

Parts ride on the belt by friction (pymunk moves a resting body with the surface velocity; the sign is "the part
moves with ``surface_velocity``" in pymunk 7). The drive is a first-order lag: after a command the belt speed
approaches the target as ``v(t) = target + (v0 - target)·exp(-t/τ)`` (τ = 50 ms, so a part stops ≈ v·τ = 2.5 mm after
the motor is switched off at 50 mm/s). The speed is written to pymunk only while it changes: the plant keeps a list
of belts in transition and steps only those, so a belt at a steady speed costs nothing per physics step.
"""

from __future__ import annotations

import math

import pymunk

from plants.components.collide import BELT_CAT, CT_BELT


class Belt:
    """One belt, top surface at ``top`` from ``x0`` to ``x0 + length`` (mm), moving along +x when commanded forward.

    Args:
        name: the belt's name (``D1``), also used as the subject of events on it.
        x0, length, top: geometry in mm (side view, y up).
        speed: nominal speed in mm/s.
        tau_s: time constant of the drive's speed response.
        friction: belt/part friction coefficient (pymunk multiplies the two shapes' values; parts use 1.0,
            so this is the pair's μ).
        reversible: whether a backward command (-1) is allowed.
        radius: segment radius (the belt's ends are rounded with it).
    """

    def __init__(
        self,
        name: str,
        x0: float,
        length: float,
        top: float,
        *,
        speed: float = 50.0,
        tau_s: float = 0.05,
        friction: float = 0.6,
        reversible: bool = False,
        radius: float = 1.0,
    ) -> None:
        if length <= 2 * radius:
            raise ValueError(f"belt {name}: length {length} mm is too short")
        if speed <= 0 or tau_s <= 0:
            raise ValueError(f"belt {name}: speed and tau_s must be > 0")
        self.name = name
        self.x0 = float(x0)
        self.length = float(length)
        self.top = float(top)
        self.speed = float(speed)
        self.tau_s = float(tau_s)
        self.friction = float(friction)
        self.reversible = reversible
        self.radius = float(radius)
        self.shape: pymunk.Segment | None = None
        self._dt = -1.0
        self._decay = 0.0
        self.reset()

    @property
    def x1(self) -> float:
        """Downstream end (mm)."""
        return self.x0 + self.length

    def reset(self) -> None:
        """Stopped, not jammed, no shape (``attach`` makes a new one)."""
        self.v = 0.0  # current speed, mm/s (signed, + = forward)
        self.target = 0.0
        self.direction = 0  # commanded: -1, 0, +1
        self.jammed = False
        self.shape = None

    def attach(self, space: pymunk.Space) -> pymunk.Segment:
        """Create the belt's static segment in ``space``."""
        r = self.radius
        seg = pymunk.Segment(space.static_body, (self.x0 + r, self.top - r), (self.x1 - r, self.top - r), r)
        seg.friction = self.friction
        seg.collision_type = CT_BELT
        seg.filter = pymunk.ShapeFilter(categories=BELT_CAT)
        seg.surface_velocity = (self.v, 0.0)
        space.add(seg)
        self.shape = seg
        return seg

    def contains(self, x: float) -> bool:
        return self.x0 <= x <= self.x1

    def command(self, direction: int) -> bool:
        """Set the commanded direction (-1, 0, +1); returns True if the speed now has to change."""
        direction = int(direction)
        if direction not in (-1, 0, 1):
            raise ValueError(f"belt {self.name}: direction must be -1, 0 or 1, not {direction}")
        if direction < 0 and not self.reversible:
            raise ValueError(f"belt {self.name} runs forward only")
        self.direction = direction
        return self._retarget()

    def jam(self, jammed: bool) -> bool:
        """Fault: the motor is blocked (the belt stops and stays stopped whatever the command)."""
        self.jammed = bool(jammed)
        return self._retarget()

    def _retarget(self) -> bool:
        self.target = 0.0 if self.jammed else self.direction * self.speed
        return self.target != self.v

    def advance(self, dt: float) -> bool:
        """One physics step of the drive: move ``v`` toward the target; returns False once it has settled."""
        if dt != self._dt:
            self._dt = dt
            self._decay = math.exp(-dt / self.tau_s)
        v = self.target + (self.v - self.target) * self._decay
        settled = abs(v - self.target) < 1e-4
        if settled:
            v = self.target
        self.v = v
        if self.shape is not None:
            self.shape.surface_velocity = (v, 0.0)
        return not settled

    @property
    def running(self) -> bool:
        return self.v != 0.0
