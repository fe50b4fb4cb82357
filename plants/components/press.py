"""A press: a ram on a vertical 1-D axis (:class:`~plants.components.axis.Axis`) with an upper and a lower limit
switch, and what its tool does to a part under it (a stroke, damage). A component on the protocol of
:mod:`plants.components.component`.

The ram's travel ``s`` runs downward from the upper end stop (``s = 0``, tool tip at ``top + overtravel``) to the
lower one (tip at ``bottom - overtravel``); the tip height is ``z = top + overtravel - s``. The axis moves it at
``speed`` with a first-order speed response (τ = 20 ms: a ram stopped at a switch coasts 0.5 mm), stalls when it is
driven against an end stop (``axis stalled``) and cannot move while jammed (``motor jammed``); both motor relays on
is ``interlock violated``. A part under the tool is an end stop too: the ram driven down onto it stalls there and
the part is ``part damaged``.

The limit switches are cams along the travel: the upper one is actuated from its make point ``top`` up to and past
the upper end stop, the lower one from ``bottom`` down past the lower end stop (a roller lever stays pressed in
overtravel), each with 0.5 mm hysteresis.

The tool and a part (the press axis at ``x`` along the belt):

* **stroke** — the tip passing down through ``stroke_depth`` counts one ``press stroke``, about the part whose
  extent along the belt contains the axis (or none); re-armed once the tip is back above ``rearm``;
* **damage** — while the tip is at or below ``stroke_depth`` the tool is in the part: a part under the tool's
  footprint that moves more than ``damage_mm`` along the belt, or that the ram is driven into, is ``part damaged``
  (once per part per stroke).

Commands are taken at the next step, both relays together, so the order in which one scan's outputs arrive never
makes a both-directions violation of its own (``S M2_DOLE`` and ``R M2_HORE`` in one scan turn the ram cleanly).

Performance: a ram at rest is not stepped at all; a moving one costs the axis's few float operations, plus one
position read per part under the tool while the tip is within reach of a part.

>>> from plants.components.component import Bench
>>> host = Bench()
>>> press = Press(parts_under=lambda lo, hi: ())
>>> _ = press.reset(host)
>>> press.z, host.sensors
(105.5, {'KS1': True, 'KS2': False})
>>> _ = press.actuate(host, "M2_DOLE", True)
>>> while not host.sensors["KS2"]:
...     host.step(press)
>>> host.now_ns // 1_000_000, [(e.kind, e.part) for e in host.events]
(1360, [('press stroke', None)])
"""

from __future__ import annotations

from collections.abc import Callable, Iterable
from typing import Any

from plants.components import draw
from plants.components.axis import Axis
from plants.components.component import Host
from plants.components.limit_switch import LimitSwitch
from plcsim.plant import Drawable, SignalSpec

PartUnder = tuple[str, float, float, float]
"""A part under the tool: (id, x of its centre, half its length, height of its top), mm."""

RAM = (110, 110, 125)
STALLED = (230, 40, 40)
SWITCH_ON = (60, 190, 60)
SWITCH_OFF = (90, 90, 90)


class Press:
    """The ram of a punching machine (see the module docstring).

    Args:
        name: the press's name, the subject of its events (``M2``).
        parts_under: ``parts_under(lo, hi)`` lists the parts whose extent along the belt overlaps ``[lo, hi]``
            (the rig's parts; called only while the tip is within reach of a part).
        x: the press axis along the belt (mm).
        top, bottom: make points of the upper and lower limit switch (tool tip height, mm).
        overtravel: the end stops lie this far beyond the switches (mm).
        speed, tau_s: ram speed (mm/s) and the drive's time constant (s).
        tool_width: the tool's footprint along the belt (mm).
        stroke_depth, rearm: the tip height that counts a stroke, and the height above which the next one is armed.
        damage_mm: how far a part may move under the tool in the stroke zone before it is damaged.
        down, up: the actuators; upper, lower: the signal names of the upper and lower limit switch.
        frame_top: where the ram's guide ends above the belt (mm), for drawing.
    """

    def __init__(
        self,
        name: str = "M2",
        *,
        parts_under: Callable[[float, float], Iterable[PartUnder]],
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
        down: str = "M2_DOLE",
        up: str = "M2_HORE",
        upper: str = "KS1",
        lower: str = "KS2",
        frame_top: float = 145.0,
    ) -> None:
        if not bottom < stroke_depth < rearm < top:
            raise ValueError(
                f"press {name}: need bottom < stroke_depth < rearm < top, got {bottom}, {stroke_depth}, {rearm}, {top}"
            )
        if overtravel <= 0:
            raise ValueError(f"press {name}: overtravel must be > 0")
        self.name = name
        self.parts_under = parts_under
        self.x = float(x)
        self.top, self.bottom = float(top), float(bottom)
        self.z0 = self.top + overtravel  # the tip at s = 0 (the upper end stop)
        self.stroke_depth, self.rearm = float(stroke_depth), float(rearm)
        self.tool_width = float(tool_width)
        self.damage_mm = float(damage_mm)
        self.down, self.up = down, up
        self.frame_top = float(frame_top)
        reach = 10.0 * overtravel  # the cams extend well past the end stops
        travel = self.z0 - (self.bottom - overtravel)
        self.upper = LimitSwitch(
            upper,
            -reach,
            overtravel,
            doc=f"press upper limit switch: True while the tool tip is at {top:g} mm or above",
        )
        self.lower = LimitSwitch(
            lower,
            self.z0 - self.bottom,
            travel + reach,
            doc=f"press lower limit switch: True while the tool tip is at {bottom:g} mm or below",
        )
        self.axis = Axis(
            name,
            0.0,
            travel,
            start=overtravel - 0.5,
            speed=speed,
            tau_s=tau_s,
            plus=down,
            minus=up,
            cams=[self.upper, self.lower],
            docs={down: f"press {name} down at {speed:g} mm/s while True", up: f"press {name} up at {speed:g} mm/s"},
        )
        self.travel = travel
        self.s_reach = self.z0 - self.rearm  # from this travel on the tool may reach a part
        self.EVENTS = Axis.EVENTS | {"press stroke", "part damaged"}
        self._cache: dict[tuple, Any] = {}

    # --- the component protocol --------------------------------------------------------------------------------
    def specs(self) -> list[SignalSpec]:
        return self.axis.specs()

    def subjects(self) -> set[str]:
        return {self.name}

    def reset(self, host: Host) -> bool:
        """At rest just above the upper switch's make point (where a stop at the switch leaves it), motor off."""
        self.axis.hi = self.travel
        self.axis.reset(host)
        self.command = {self.down: False, self.up: False}
        self.pending = False
        self.armed = True  # the next pass through stroke_depth counts a stroke
        self.strokes = 0
        self.engaged: dict[str, float] = {}  # parts under the tool in the stroke zone -> x when it got there
        self.damaged: set[str] = set()  # parts damaged in this stroke
        return False

    def actuate(self, host: Host, signal: str, value: Any) -> bool:
        """A relay changed: taken, with the other one, at the next step."""
        value = bool(value)
        if self.command[signal] != value:
            self.command[signal] = value
            self.pending = True
        return self.pending

    def jam(self, host: Host, jammed: bool) -> bool:
        """Fault: the ram is stuck where it is (a jammed guide stops it at once); freed, it moves again as commanded."""
        if jammed:
            self.axis.v = 0.0
        return self.axis.jam(host, jammed)

    def shift_cam(self, name: str, dx: float) -> None:
        """Fault: a limit switch mounted ``dx`` mm off its place (along the travel, + = lower)."""
        self.axis.shift_cam(name, dx)

    def advance(self, host: Host, dt: float) -> bool:
        axis = self.axis
        if self.pending:  # switch the released relay first: the axis sees both on only if both are commanded
            self.pending = False
            for signal in sorted(self.command, key=lambda k: self.command[k]):
                axis.actuate(host, signal, self.command[signal])
        under: list[PartUnder] = []
        against = None
        if axis.s + abs(axis.v) * dt >= self.s_reach:  # the tip is within reach of a part's top
            half = self.tool_width / 2
            under = list(self.parts_under(self.x - half, self.x + half))
            tops = [(p[3], p[0]) for p in under if self.z0 - p[3] < self.travel]
            if tops:
                floor, against = max(tops)
                axis.hi = max(axis.s, self.z0 - floor)  # a part never lifts the ram
            else:
                axis.hi = self.travel
        elif axis.hi != self.travel:
            axis.hi = self.travel
        was_stalled = axis.stalled
        busy = axis.advance(host, dt)
        if against is not None and axis.stalled and not was_stalled and axis.s >= axis.hi:
            self._damage(host, against, "the ram was driven into it")
        z = self.z0 - axis.s
        if z <= self.stroke_depth:
            if self.armed:
                self.armed = False
                self.strokes += 1
                self._stroke(host, under)
            self._watch(host, under)
        elif self.engaged or self.damaged:
            self.engaged.clear()
            self.damaged.clear()
        if z > self.rearm:
            self.armed = True
        return busy or (z <= self.stroke_depth and bool(under))  # a lowered tool watches the parts under it

    # --- state ---------------------------------------------------------------------------------------------
    @property
    def z(self) -> float:
        """Tool tip height above the base (mm)."""
        return self.z0 - self.axis.s

    @property
    def at_top(self) -> bool:
        """The upper switch is actuated (the physical top, whatever the switch is called)."""
        return self.upper.actuated

    @property
    def driven(self) -> bool:
        """A relay of the motor is on."""
        return self.command[self.down] or self.command[self.up]

    def _stroke(self, host: Host, under: list[PartUnder]) -> None:
        on_axis = [p for p in under if abs(p[1] - self.x) <= p[2]]
        part = min(on_axis, key=lambda p: abs(p[1] - self.x), default=None)
        data: dict[str, Any] = {"stroke": self.strokes}
        if part is not None:
            data["offset_mm"] = round(part[1] - self.x, 3)
        host.emit("press stroke", self.name, part[0] if part else None, **data)

    def _watch(self, host: Host, under: list[PartUnder]) -> None:
        """A part under the tool in the stroke zone must not move."""
        for pid, x, _half, _top in under:
            x0 = self.engaged.setdefault(pid, x)
            if abs(x - x0) > self.damage_mm:
                self._damage(host, pid, f"it moved {x - x0:+.1f} mm under the lowered tool")

    def _damage(self, host: Host, pid: str, cause: str) -> None:
        if pid not in self.damaged:
            self.damaged.add(pid)
            host.emit("part damaged", self.name, pid, cause=cause, z=round(self.z, 3))

    # --- drawing ---------------------------------------------------------------------------------------------
    # The ram carries an arm with a dog (a cam bar) that runs between the two limit switches: at the top the dog's
    # upper end presses the upper switch's lever, at the bottom its lower end presses the lower one's. Heights are
    # relative to the tool tip; the switches sit where the dog meets them at their make points.
    DOG_X, DOG_W, DOG_LO, DOG_HI, ARM_LO, ARM_HI = 26.0, 5.0, 8.0, 20.0, 12.0, 16.0

    def _switch_height(self, sw: LimitSwitch) -> float:
        """Where the dog meets switch ``sw``'s lever: its make point (shifted as mounted) plus the dog's end."""
        if sw is self.upper:
            return self.z0 - (sw.hi + sw.dx) + self.DOG_HI
        return self.z0 - (sw.lo + sw.dx) + self.DOG_LO

    def static_drawables(self) -> list[Drawable]:
        x = self.x + self.DOG_X + 17.0  # the switches' mounting bar, hung from the press frame
        low = self._switch_height(self.lower) - 8.0
        out = [
            draw.polygon(f"press/{self.name}/switch_bar", draw.rect(x, low, x + 3.0, self.frame_top), draw.FRAME),
            draw.label(f"press/{self.name}/label", self.x - 30.0, self.frame_top + 6.0, self.name),
        ]
        for sw, side in ((self.upper, 1.0), (self.lower, -1.0)):
            z = self._switch_height(sw)
            out.append(draw.label(f"press/switches/{sw.name}/label", self.x + 52.0, z + 3.0 + 4.0 * side, sw.name))
        return out

    def dynamic_drawables(self) -> list[Drawable]:
        cache, axis, half = self._cache, self.axis, self.tool_width / 2
        key = ("ram", axis.s, axis.stalled)
        ram = cache.get(key) if axis.v == 0.0 else None
        if ram is None:
            x, z = self.x, self.z
            box = draw.rect(x - half, z, x + half, self.frame_top)
            ram = [
                Drawable(f"press/{self.name}/ram", "polygon", box, STALLED if axis.stalled else RAM),
                draw.polygon(f"press/{self.name}/dog", self._dog(x + half, z), RAM),
            ]
            if axis.v == 0.0:  # a ram at rest: one drawable per pose, shared by every frame
                cache[key] = ram
        out = list(ram)
        for sw, side in ((self.upper, 1.0), (self.lower, -1.0)):
            key = ("switch", sw.name, sw.actuated, sw.dx)
            d = cache.get(key)
            if d is None:
                d = cache[key] = draw.polygon(
                    f"press/switches/{sw.name}",
                    self._lever(self._switch_height(sw), side),
                    SWITCH_ON if sw.actuated else SWITCH_OFF,
                )
            out.append(d)
        return out

    def _dog(self, x0: float, z: float) -> list[tuple[float, float]]:
        """The arm from the ram's side at ``x0`` and the dog at its end, for the tool tip at ``z``."""
        x1, x2 = self.x + self.DOG_X, self.x + self.DOG_X + self.DOG_W
        return [
            (x0, z + self.ARM_LO),
            (x1, z + self.ARM_LO),
            (x1, z + self.DOG_LO),
            (x2, z + self.DOG_LO),
            (x2, z + self.DOG_HI),
            (x1, z + self.DOG_HI),
            (x1, z + self.ARM_HI),
            (x0, z + self.ARM_HI),
        ]

    def _lever(self, h: float, side: float) -> list[tuple[float, float]]:
        """A limit switch beside the dog's track: its lever reaches into the track at height ``h``, its body lies
        above (``side`` 1, the upper switch) or below (-1) the lever."""
        x = self.x + self.DOG_X + 3.0
        return [(x, h), (x + 14.0, h), (x + 14.0, h + 6.0 * side), (x + 5.0, h + 6.0 * side), (x + 5.0, h + 1.5 * side)]
