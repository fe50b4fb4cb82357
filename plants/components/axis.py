"""A 1-D kinematic axis: a carriage (a press ram, a crane axis) driven by one or two motor outputs between end stops.

The position ``s`` (mm) moves at the commanded speed toward ``+`` (actuator ``plus``) or ``-`` (actuator ``minus``)
with a first-order speed response (``tau_s``; 0 = at speed at once). Both commanded at once is a wiring fault of the
program: the axis stops and logs ``interlock violated``. At a mechanical end stop (``lo``/``hi``) the carriage
stops; driven on against it, the motor **stalls**: one ``axis stalled`` event when the stall begins (data: the end,
the position), and :attr:`Axis.stalled` stays True while the command pushes into the stop. A jammed drive
(:meth:`Axis.jam`) does not move whatever the command (``motor jammed``).

Cams are :class:`~plants.components.limit_switch.LimitSwitch` zones on ``s``; each is a sensor of the rig, updated
as the axis moves. The axis is kinematic (no pymunk body); a rig that needs the carriage in its space reads
:attr:`Axis.s` (e.g. a press checks for a part under the ram).

>>> from plants.components.limit_switch import LimitSwitch
>>> ram = Axis("M2", 0.0, 39.0, start=3.0, speed=25.0, plus="M2_DOLE", minus="M2_HORE",
...            cams=[LimitSwitch("KS1", 2.0, 4.0), LimitSwitch("KS2", 35.0, 37.0)])
>>> from plants.components.component import Bench
>>> host = Bench(); _ = ram.reset(host); host.sensors
{'KS1': True, 'KS2': False}
>>> _ = ram.actuate(host, "M2_DOLE", True)
>>> while not host.sensors["KS2"]:
...     host.step(ram)
>>> round(host.now_ns / 1e9, 3), host.sensors  # 32 mm at 25 mm/s, + 1 step for the rounding of s
(1.281, {'KS1': False, 'KS2': True})
>>> for _ in range(200): host.step(ram)
>>> ram.s, ram.stalled, [(e.kind, e.data["end"]) for e in host.events]
(39.0, True, [('axis stalled', 'hi')])
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

from plants.components import draw
from plants.components.component import Host
from plants.components.limit_switch import LimitSwitch, quiet_range
from plcsim.plant import Drawable, SignalSpec


class Axis:
    """One axis between mechanical end stops ``lo`` < ``hi`` (mm).

    Args:
        name: the axis (subject of its events).
        lo: the lower end stop.
        hi: the upper end stop.
        start: position after reset (default ``lo``).
        speed: travel speed in mm/s.
        tau_s: time constant of the speed response (0: instant).
        plus: the actuator driving toward ``hi`` (may be None).
        minus: the actuator driving toward ``lo`` (may be None).
        cams: limit switches along ``s`` (their names are the rig's sensors).
        docs: doc strings of the actuators.
        drawing: ``(x, y, dx, dy, width, length)`` — draw the carriage as a bar of that size whose reference point
            is at ``(x, y) + s·(dx, dy)`` (None: not drawn).
    """

    EVENTS = frozenset({"axis stalled", "interlock violated", "motor jammed"})

    def __init__(
        self,
        name: str,
        lo: float,
        hi: float,
        *,
        start: float | None = None,
        speed: float,
        tau_s: float = 0.0,
        plus: str | None = None,
        minus: str | None = None,
        cams: Sequence[LimitSwitch] = (),
        docs: dict[str, str] | None = None,
        drawing: tuple[float, float, float, float, float, float] | None = None,
    ) -> None:
        if hi <= lo:
            raise ValueError(f"axis {name}: hi {hi} must be above lo {lo}")
        if speed <= 0 or tau_s < 0:
            raise ValueError(f"axis {name}: speed must be > 0 and tau_s >= 0")
        self.name = name
        self.lo, self.hi = float(lo), float(hi)
        self.start = self.lo if start is None else float(start)
        if not self.lo <= self.start <= self.hi:
            raise ValueError(f"axis {name}: start {self.start} outside [{lo}, {hi}]")
        self.speed = float(speed)
        self.tau_s = float(tau_s)
        self.plus, self.minus = plus, minus
        self.cams = list(cams)
        self.docs = dict(docs or {})
        self.drawing = drawing
        self._decay: tuple[float, float] = (-1.0, 0.0)

    def specs(self) -> list[SignalSpec]:
        out = [
            SignalSpec(a, "actuator", doc=self.docs.get(a, f"drives {self.name} toward {end} at {self.speed:g} mm/s"))
            for a, end in ((self.plus, "hi"), (self.minus, "lo"))
            if a is not None
        ]
        out += [
            SignalSpec(c.name, "sensor", doc=c.doc or f"cam on {self.name}: True in [{c.lo:g}, {c.hi:g}] mm")
            for c in self.cams
        ]
        return out

    def subjects(self) -> set[str]:
        return {self.name}

    def reset(self, host: Host) -> bool:
        self.s = self.start
        self.v = 0.0
        self.command = {a: False for a in (self.plus, self.minus) if a is not None}
        self.direction = 0
        self.jammed = False
        self.stalled = False
        self._recheck = False
        for cam in self.cams:
            cam.reset()
            cam.update(self.s)
            host.sensors[cam.name] = cam.actuated
        self._quiet = quiet_range(self.cams, self.s)
        return False

    def actuate(self, host: Host, signal: str, value: Any) -> bool:
        value = bool(value)
        if self.command[signal] == value:
            return False
        self.command[signal] = value
        fwd = bool(self.plus and self.command[self.plus])
        back = bool(self.minus and self.command[self.minus])
        if fwd and back:
            host.emit("interlock violated", self.name, reason="both directions commanded")
        self.direction = 0 if fwd == back else (1 if fwd else -1)
        return True

    def jam(self, host: Host, jammed: bool = True) -> bool:
        """Fault: the drive is blocked (it does not move whatever the command)."""
        jammed = bool(jammed)
        if jammed and not self.jammed:
            host.emit("motor jammed", self.name, commanded=self.direction != 0)
        self.jammed = jammed
        return True

    def shift_cam(self, name: str, dx: float) -> None:
        """Fault: cam ``name`` is mounted ``dx`` mm off its place (takes effect at the next move)."""
        next(c for c in self.cams if c.name == name).shift(dx)
        self._recheck = True

    def advance(self, host: Host, dt: float) -> bool:
        target = 0.0 if self.jammed else self.direction * self.speed
        if self.tau_s > 0:
            if self._decay[0] != dt:
                self._decay = (dt, math.exp(-dt / self.tau_s))
            v = target + (self.v - target) * self._decay[1]
            if abs(v - target) < 1e-4:
                v = target
        else:
            v = target
        s = self.s + v * dt
        end = None
        if s >= self.hi:
            s, end = self.hi, "hi"
        elif s <= self.lo:
            s, end = self.lo, "lo"
        pushing = end is not None and target != 0.0 and (target > 0) == (end == "hi")
        if pushing:
            v = 0.0
            if not self.stalled:
                self.stalled = True
                host.emit("axis stalled", self.name, end=end, position=s)
        else:
            self.stalled = False
        self.v = v
        if s != self.s or self._recheck:
            lo, hi = self._quiet
            if self._recheck or not lo <= s <= hi:
                for cam in self.cams:
                    if cam.update(s):
                        host.sensors[cam.name] = cam.actuated
                self.s = s
                self._quiet = quiet_range(self.cams, self.s)
            self.s, self._recheck = s, False
        return v != 0.0 or target != 0.0

    def static_drawables(self) -> list[Drawable]:
        return []

    def dynamic_drawables(self) -> list[Drawable]:
        if self.drawing is None:
            return []
        x, y, dx, dy, width, length = self.drawing
        cx, cy = x + self.s * dx, y + self.s * dy
        nx, ny = -dy, dx  # across the axis
        hw = width / 2
        corners = [
            (cx + nx * hw, cy + ny * hw),
            (cx - nx * hw, cy - ny * hw),
            (cx - nx * hw - dx * length, cy - ny * hw - dy * length),
            (cx + nx * hw - dx * length, cy + ny * hw - dy * length),
        ]
        color = draw.BEAM_CUT if self.stalled else draw.BELT_RUNNING if self.v else draw.BELT
        return [draw.polygon(f"axes/{self.name}", corners, color, self.name)]
