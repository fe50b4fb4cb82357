"""A side-view conveyor belt: a static segment whose ``surface_velocity`` is the belt speed; a component of a
side-view rig (:mod:`plants.components.component`).

Parts ride on the belt by friction (pymunk moves a resting body with the surface velocity; the sign is "the part
moves with ``surface_velocity``" in pymunk 7). The drive is a first-order lag: after a command the belt speed
approaches the target as ``v(t) = target + (v0 - target)·exp(-t/τ)`` (τ = 50 ms, so a part stops ≈ v·τ = 2.5 mm after
the motor is switched off at 50 mm/s). The speed is written to pymunk only while it changes: the belt is a busy
component only until it has settled, so a belt at a steady speed costs nothing per physics step.

The motor has one relay per direction (``forward``, and ``backward`` on a reversible belt). Their commands are taken
together at the start of the next physics step (:meth:`Belt.commit`): the outputs of one scan reach the plant one
after the other, and a reversal (``R M1_VZAD`` and ``S M1_VPRED`` in one scan, in either order) must not look like
both relays on at once. Only both relays commanded in the same scan is ``interlock violated`` (the motor then
stops), as a real relay H-bridge would short.

>>> from plants.components.component import Bench
>>> host = Bench()
>>> host.space = pymunk.Space()
>>> m1 = Belt("M1", 0.0, 280.0, 50.0, speed=40.0, forward="FWD", backward="BACK")
>>> _ = m1.reset(host)
>>> _ = m1.actuate(host, "FWD", True); host.step(m1)
>>> _ = m1.actuate(host, "BACK", True); _ = m1.actuate(host, "FWD", False); host.step(m1)
>>> m1.target, host.events
(-40.0, [])
>>> _ = m1.actuate(host, "FWD", True); host.step(m1)
>>> m1.target, [(e.kind, e.subject, e.data["reason"]) for e in host.events]
(0.0, [('interlock violated', 'M1', 'both directions commanded')])
"""

from __future__ import annotations

import math
from typing import Any

import pymunk

from plants.components import chipmunk, draw
from plants.components.collide import BELT_CAT, CT_BELT
from plants.components.component import Host
from plcsim.plant import Drawable, SignalSpec


class Belt:
    """One belt, top surface at ``top`` from ``x0`` to ``x0 + length`` (mm), moving along +x when commanded forward.

    Args:
        name: the belt's name (``D1``), also used as the subject of events on it.
        x0: where the belt starts (mm; side view, y up).
        length: its length (mm).
        top: the height of its top surface (mm).
        speed: nominal speed in mm/s.
        tau_s: time constant of the drive's speed response.
        friction: belt/part friction coefficient (pymunk multiplies the two shapes' values; parts use 1.0,
            so this is the pair's μ).
        reversible: whether a backward command (-1) is allowed (implied by a ``backward`` actuator).
        radius: segment radius (the belt's ends are rounded with it).
        forward: the actuator of the motor's forward direction (None: not driven from the PLC).
        backward: the actuator of its backward direction (None: none).
        docs: doc strings of the actuators.
    """

    EVENTS = frozenset({"interlock violated", "motor jammed"})
    layer = "under"
    """Drawn under the parts (a rig draws its components in two layers around them)."""
    carries_parts = True
    """Parts rest on it: the rig places parts on its top and knows which belt a part is on."""

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
        forward: str | None = None,
        backward: str | None = None,
        docs: dict[str, str] | None = None,
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
        self.reversible = reversible or backward is not None
        self.radius = float(radius)
        self.forward, self.backward = forward, backward
        self.docs = dict(docs or {})
        self.shape: pymunk.Segment | None = None
        self._dt = -1.0
        self._decay = 0.0
        self._reset_state()

    @property
    def x1(self) -> float:
        """Downstream end (mm)."""
        return self.x0 + self.length

    @property
    def actuators(self) -> tuple[str, ...]:
        return tuple(a for a in (self.forward, self.backward) if a is not None)

    # --- the component protocol --------------------------------------------------------------------------------
    def specs(self) -> list[SignalSpec]:
        return [SignalSpec(a, "actuator", doc=self.docs.get(a, "")) for a in self.actuators]

    def subjects(self) -> set[str]:
        """Its events name the belt, or the actuator a fault was injected on."""
        return {self.name, *self.actuators}

    def reset(self, host: Host) -> bool:
        """Stopped, not jammed, no command; a new segment in ``host.space``."""
        self._reset_state()
        self.attach(host.space)
        return False

    def actuate(self, host: Host, signal: str, value: Any) -> bool:
        """A relay changed: taken, with the other one, at the start of the next step (:meth:`commit`)."""
        value = bool(value)
        if self.commands[signal] != value:
            self.commands[signal] = value
            host.defer(self)
        return False

    def commit(self, host: Host) -> bool:
        """Take both relays' commands at once; True if the speed now has to change."""
        fwd = bool(self.forward and self.commands[self.forward])
        back = bool(self.backward and self.commands[self.backward])
        if fwd and back:
            host.emit("interlock violated", self.name, reason="both directions commanded")
        return self.command(0 if fwd == back else (1 if fwd else -1))

    def jam(self, host: Host, jammed: bool, subject: str | None = None) -> bool:
        """Fault: the motor is blocked (the belt stops and stays stopped whatever the command); ``motor jammed``
        about ``subject`` (the name the fault was given: the belt or one of its actuators)."""
        was = self.jammed
        self.jammed = bool(jammed)
        if self.jammed and not was:
            host.emit("motor jammed", subject or self.name, belt=self.name, commanded=any(self.commands.values()))
        return self._retarget()

    def advance(self, host: Host, dt: float) -> bool:
        return self.drive(dt)

    def static_drawables(self) -> list[Drawable]:
        out = []
        for k, xl in enumerate((self.x0 + 15.0, self.x1 - 23.0)):
            leg = draw.rect(xl, 0.0, xl + 8.0, self.top - 10.0)
            out.append(draw.polygon(f"frame/legs/{self.name}/{k}", leg, draw.FRAME))
        out.append(
            draw.polygon(
                f"belt/{self.name}", draw.stadium(self.x0, self.x1, self.top - 10.0, self.top), draw.BELT, self.name
            )
        )
        out.append(draw.label(f"belt/{self.name}/label", 0.5 * (self.x0 + self.x1), self.top - 20.0, self.name))
        return out

    def dynamic_drawables(self) -> list[Drawable]:
        """An arrow in the running direction (one drawable per direction, shared by every frame)."""
        if self.v == 0.0:
            return []
        forward = self.v > 0
        arrow = self._arrows.get(forward)
        if arrow is None:
            xm = 0.5 * (self.x0 + self.x1)
            d = 15.0 if forward else -15.0
            arrow = self._arrows[forward] = draw.arrow(
                f"belt/{self.name}/direction", xm - d, xm + d, self.top - 5.0, draw.BELT_RUNNING
            )
        return [arrow]

    # --- the drive ---------------------------------------------------------------------------------------------
    def _reset_state(self) -> None:
        self.v = 0.0  # current speed, mm/s (signed, + = forward)
        self.target = 0.0
        self.direction = 0  # driven: -1, 0, +1
        self.jammed = False
        self.commands = dict.fromkeys(self.actuators, False)
        self.shape = None
        self._arrows: dict[bool, Drawable] = {}

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
        self._h = chipmunk.shape_handle(seg)  # written in every step while the drive settles
        return seg

    def contains(self, x: float) -> bool:
        return self.x0 <= x <= self.x1

    def command(self, direction: int) -> bool:
        """Drive in ``direction`` (-1, 0, +1); returns True if the speed now has to change."""
        direction = int(direction)
        if direction not in (-1, 0, 1):
            raise ValueError(f"belt {self.name}: direction must be -1, 0 or 1, not {direction}")
        if direction < 0 and not self.reversible:
            raise ValueError(f"belt {self.name} runs forward only")
        self.direction = direction
        return self._retarget()

    def _retarget(self) -> bool:
        self.target = 0.0 if self.jammed else self.direction * self.speed
        return self.target != self.v

    def drive(self, dt: float) -> bool:
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
            chipmunk.set_surface_velocity(self._h, (v, 0.0))
        return not settled

    @property
    def running(self) -> bool:
        return self.v != 0.0
