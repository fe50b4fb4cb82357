"""A press ram on a vertical 1-D axis: one motor with a relay per direction, an upper and a lower limit switch,
mechanical end stops, a stall when it is driven against one of them (or against a part), and the tool's effect
on a part under it (a stroke, damage).

The ram is kinematic (no pymunk body): its tool tip height ``z`` (mm above the base) follows the motor with a
first-order speed response, ``v → command · speed`` with time constant τ, so a ram stopped at a limit switch
coasts ``v·τ`` (0.5 mm at 25 mm/s, τ = 20 ms, a small worm-geared motor). It cannot leave
``[z_min, z_max]`` (the end stops, ``overtravel`` mm beyond each switch) and it cannot go below the top of a part
under the tool. A motor that is driven against an end stop or a part **stalls**: the ram stands still and the
press reports ``motor stalled`` once per stall, with what it stalled against. A jammed ram (a fault the scenario
injects, reported by the plant as ``motor jammed``) stands wherever it was, driven or not.

The limit switches are cams along the travel: the upper one is actuated from its make point ``top`` up to and past
the upper end stop, the lower one from ``bottom`` down past the lower end stop (a roller lever stays pressed in
overtravel), each with 0.5 mm hysteresis (:class:`~plants.components.limit_switch.LimitSwitch`).

The tool and a part (plant coordinates, the press axis at ``x``):

* **stroke** — the tip passing down through ``stroke_depth`` counts one ``press stroke``, about the part whose
  extent along the belt contains the axis (or none); re-armed once the tip is back above ``rearm``;
* **damage** — while the tip is at or below ``stroke_depth`` the tool is in the part: a part under the tool's
  footprint that moves more than ``damage_mm`` along the belt, or that the ram is driven into, is ``part damaged``
  (once per part per stroke).

Performance: a ram at rest costs nothing per step (the plant skips it); a moving one a few float operations,
plus one position read per part under the tool while the tool is in the stroke zone.

>>> press = Press(upper="KS1", lower="KS2")
>>> press.z, press.switches["KS1"].actuated, press.switches["KS2"].actuated
(105.5, True, False)
>>> press.command(-1)
>>> events = []
>>> t = 0
>>> while not press.switches["KS2"].actuated:
...     t += 1
...     _ = press.advance(0.001, t * 1_000_000, lambda: (), events)
>>> t, [e.kind for e in events]
(1360, ['press stroke'])
"""

from __future__ import annotations

import math
from collections.abc import Callable, Iterable
from typing import Any

from plants.components.limit_switch import LimitSwitch
from plcsim.plant import PlantEvent

PartUnder = tuple[str, float, float, float]
"""A part under the tool: (id, x of its centre, half its length, height of its top), mm."""


class Press:
    """The ram of a punching machine (see the module docstring).

    Args:
        name: the press's name, the subject of its events (``M2``).
        x: the press axis along the belt (mm).
        top, bottom: make points of the upper and lower limit switch (tool tip height, mm).
        overtravel: the end stops lie this far beyond the switches (mm).
        speed, tau_s: ram speed (mm/s) and the drive's time constant (s).
        tool_width: the tool's footprint along the belt (mm).
        stroke_depth, rearm: the tip height that counts a stroke, and the height above which the next one is armed.
        damage_mm: how far a part may move under the tool in the stroke zone before it is damaged.
        upper, lower: the signal names of the upper and lower limit switch.
        hysteresis: of both switches (mm).
    """

    def __init__(
        self,
        name: str = "M2",
        *,
        x: float = 215.0,
        top: float = 105.0,
        bottom: float = 72.0,
        overtravel: float = 3.0,
        speed: float = 25.0,
        tau_s: float = 0.02,
        tool_width: float = 12.0,
        stroke_depth: float = 75.0,
        rearm: float = 80.0,
        damage_mm: float = 1.0,
        upper: str = "KS1",
        lower: str = "KS2",
        hysteresis: float = 0.5,
    ) -> None:
        if not bottom < stroke_depth < rearm < top:
            raise ValueError(
                f"press {name}: need bottom < stroke_depth < rearm < top, got {bottom}, {stroke_depth}, {rearm}, {top}"
            )
        if speed <= 0 or tau_s <= 0 or overtravel <= 0:
            raise ValueError(f"press {name}: speed, tau_s and overtravel must be > 0")
        self.name = name
        self.x = float(x)
        self.top = float(top)
        self.bottom = float(bottom)
        self.z_max = self.top + overtravel
        self.z_min = self.bottom - overtravel
        self.speed = float(speed)
        self.tau_s = float(tau_s)
        self.tool_width = float(tool_width)
        self.stroke_depth = float(stroke_depth)
        self.rearm = float(rearm)
        self.damage_mm = float(damage_mm)
        reach = 10.0 * overtravel  # the cams extend well past the end stops
        self.upper = LimitSwitch(
            upper,
            self.top,
            self.z_max + reach,
            hysteresis=hysteresis,
            doc=f"press upper limit switch: True while the tool tip is at {self.top:g} mm or above",
        )
        self.lower = LimitSwitch(
            lower,
            self.z_min - reach,
            self.bottom,
            hysteresis=hysteresis,
            doc=f"press lower limit switch: True while the tool tip is at {self.bottom:g} mm or below",
        )
        self.switches = {self.upper.name: self.upper, self.lower.name: self.lower}
        self._dt = -1.0
        self._decay = 0.0
        self.reset()

    def reset(self) -> None:
        """At rest just above the upper switch's make point (where a stop at the switch leaves it), motor off."""
        self.z = self.top + 0.5
        self.v = 0.0
        self.direction = 0  # commanded: -1 down, 0, +1 up
        self.jammed = False
        self.stalled: str | None = None  # what the driven ram stands against
        self.armed = True  # the next pass through stroke_depth counts a stroke
        self.strokes = 0
        self.engaged: dict[str, float] = {}  # parts under the tool in the stroke zone -> x when it got there
        self.damaged: set[str] = set()  # parts damaged in this stroke
        for sw in self.switches.values():
            sw.reset()
            sw.update(self.z)

    @property
    def at_top(self) -> bool:
        """The upper switch is actuated (the physical top, whatever the switch is called)."""
        return self.upper.actuated

    @property
    def idle(self) -> bool:
        """Nothing to advance: at rest, and not driven or blocked for good (an end stop, a jam; a part may go away)."""
        return self.v == 0.0 and (
            self.direction == 0 or self.jammed or self.stalled in ("upper end stop", "lower end stop")
        )

    def command(self, direction: int) -> None:
        """Drive up (+1), down (-1) or stop (0); a change of command ends a stall."""
        if direction not in (-1, 0, 1):
            raise ValueError(f"press {self.name}: direction must be -1, 0 or 1, not {direction}")
        if direction != self.direction:
            self.direction = direction
            self.stalled = None

    def jam(self, jammed: bool) -> None:
        """Fault: the ram is blocked where it is (a jammed guide); freed, it moves again as commanded."""
        self.jammed = bool(jammed)
        if self.jammed:
            self.v = 0.0

    def advance(
        self, dt: float, now_ns: int, parts_under: Callable[[], Iterable[PartUnder]], events: list[PlantEvent]
    ) -> bool:
        """One step of ``dt`` s ending at ``now_ns``; returns True if a limit switch changed.

        ``parts_under()`` lists the parts whose extent overlaps the tool's footprint; it is called only while the
        tip is low enough to reach a part.
        """
        if self.jammed:
            return False
        if dt != self._dt:
            self._dt = dt
            self._decay = math.exp(-dt / self.tau_s)
        target = self.direction * self.speed
        v = target + (self.v - target) * self._decay
        if abs(v - target) < 1e-4:
            v = target
        z = self.z + v * dt
        under: list[PartUnder] = []
        floor, against = self.z_min, "lower end stop"
        if z <= self.rearm:
            under = list(parts_under())
            for pid, _x, _half, part_top in under:
                if part_top > floor:
                    floor, against = part_top, f"part {pid}"
        if z >= self.z_max and v > 0:
            z, v = self.z_max, 0.0
            self._stall("upper end stop", now_ns, events)
        elif z <= floor and v < 0:
            z, v = floor, 0.0
            self._stall(against, now_ns, events)
            if against.startswith("part "):
                self._damage(against[5:], "the ram was driven into it", now_ns, events)
        elif v != 0.0:
            self.stalled = None
        self.z, self.v = z, v
        if z <= self.stroke_depth:
            if self.armed:
                self.armed = False
                self.strokes += 1
                self._stroke(under, now_ns, events)
            self._watch(under, now_ns, events)
        elif self.engaged or self.damaged:
            self.engaged.clear()
            self.damaged.clear()
        if z > self.rearm:
            self.armed = True
        changed = self.upper.update(z)
        return self.lower.update(z) or changed

    def _stall(self, against: str, now_ns: int, events: list[PlantEvent]) -> None:
        if self.stalled == against:
            return
        self.stalled = against
        events.append(
            PlantEvent(
                now_ns,
                "motor stalled",
                self.name,
                None,
                {"against": against, "z": round(self.z, 3), "direction": "up" if self.direction > 0 else "down"},
            )
        )

    def _stroke(self, under: list[PartUnder], now_ns: int, events: list[PlantEvent]) -> None:
        on_axis = [p for p in under if abs(p[1] - self.x) <= p[2]]
        part = min(on_axis, key=lambda p: abs(p[1] - self.x), default=None)
        data: dict[str, Any] = {"stroke": self.strokes}
        if part is not None:
            data["offset_mm"] = round(part[1] - self.x, 3)
        events.append(PlantEvent(now_ns, "press stroke", self.name, part[0] if part else None, data))

    def _watch(self, under: list[PartUnder], now_ns: int, events: list[PlantEvent]) -> None:
        """A part under the tool in the stroke zone must not move."""
        for pid, x, _half, _top in under:
            x0 = self.engaged.setdefault(pid, x)
            if abs(x - x0) > self.damage_mm:
                self._damage(pid, f"it moved {x - x0:+.1f} mm under the lowered tool", now_ns, events)

    def _damage(self, pid: str, cause: str, now_ns: int, events: list[PlantEvent]) -> None:
        if pid in self.damaged:
            return
        self.damaged.add(pid)
        events.append(PlantEvent(now_ns, "part damaged", self.name, pid, {"cause": cause, "z": round(self.z, 3)}))
