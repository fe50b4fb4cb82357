"""A rope winch driven through a frequency converter (VFD): a carriage (a skip) pulled along a track by a rope.

The position ``s`` (mm along the track, + = up) follows the converter's output frequency ``f`` (Hz, signed: + winds
the rope, the carriage goes up):

* **direction** — ``up`` or ``down`` selects the sense; **both** at once is a converter fault: it trips to 0 Hz,
  the brake falls in, and ``converter fault`` is logged once when the fault begins (it clears itself when the
  commands agree again);
* **speed** — two fixed frequencies, ``fast`` and ``slow`` (both bits: fast); a direction with **no speed bit** is
  0 Hz with the brake held and a ``converter warning`` once when it begins;
* **ramps** — the frequency moves toward the set point at ``ramp_hz_s`` (0 → fast in 0.5 s at 100 Hz/s);
* **brake** — held whenever no direction is active (or the converter faults, or gives 0 Hz): the carriage stops
  at ``brake_mm_s2``, the frequency follows it down, and a new start ramps up from standstill;
* **speed** — ``v = f / f_fast · v_fast · (1 - slip · load · sign(f))``: a loaded carriage runs slow by the motor's
  slip going up (and as much fast going down); ``load`` (0..1) is set by the rig;
* **end buffers** — the track ends at ``lo`` and ``hi``; a carriage that reaches one stops there (``end stop hit``,
  with the speed of the impact) and a drive that keeps pulling stalls against it;
* **rope jam** — :meth:`jam` (an overload, a jammed sheave) stops the carriage where it is whatever the command
  (``motor jammed``) until it is freed.

The cam switches are :class:`~plants.components.limit_switch.LimitSwitch` zones on ``s``; when one makes,
``speed measured`` is logged with the carriage's speed (``data["speed_mm_s"]``, signed), so a check can grade the
speed at a sensor (the skip's arrival at the top at the slow speed). The winch is kinematic (no pymunk body).

>>> from plants.components.component import Bench
>>> from plants.components.limit_switch import LimitSwitch, quiet_range
>>> w = Winch("SKIP", -25.0, 1030.0, start=8.0, cams=[LimitSwitch("TOP", 990.0, 1010.0)])
>>> host = Bench(); _ = w.reset(host)
>>> for sig in ("UP", "FAST"): _ = w.actuate(host, sig, True)
>>> while not host.sensors["TOP"]:
...     host.step(w)
>>> round(host.now_ns / 1e9, 2), [(e.kind, round(e.data["speed_mm_s"], 1)) for e in host.events]
(24.8, [('speed measured', 40.0)])

(982 mm at 40 mm/s, plus half the 0.5 s ramp.)
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import Any

from plants.components.component import Host
from plants.components.limit_switch import LimitSwitch, quiet_range
from plcsim.plant import Drawable, SignalSpec


class Winch:
    """The winch, its converter and the carriage's track (see the module docstring).

    Args:
        name: the carriage (subject of its events); the converter's events are about ``converter``.
        lo: the lower end buffer (mm along the track).
        hi: the upper end buffer.
        start: the position after reset.
        v_fast: the carriage speed at the fast fixed frequency (mm/s, unloaded).
        v_slow: the speed at the slow one.
        f_fast: the fast frequency (Hz); the slow one is ``f_fast · v_slow / v_fast``.
        ramp_hz_s: the converter's ramp (Hz/s).
        brake_mm_s2: the brake's deceleration (mm/s²).
        slip: the speed lost at full load (fraction).
        up: the actuator (PLC output) of the direction up.
        down: the actuator of the direction down.
        fast: the actuator of the fast fixed frequency.
        slow: the actuator of the slow fixed frequency.
        cams: the limit switches along the track.
        converter: the converter's name (subject of its events).
    """

    EVENTS = frozenset({"converter fault", "converter warning", "end stop hit", "motor jammed", "speed measured"})

    def __init__(
        self,
        name: str,
        lo: float,
        hi: float,
        *,
        start: float = 0.0,
        v_fast: float = 40.0,
        v_slow: float = 25.0,
        f_fast: float = 50.0,
        ramp_hz_s: float = 100.0,
        brake_mm_s2: float = 250.0,
        slip: float = 0.03,
        up: str = "UP",
        down: str = "DOWN",
        fast: str = "FAST",
        slow: str = "SLOW",
        cams: Sequence[LimitSwitch] = (),
        converter: str = "converter",
    ) -> None:
        if not lo < start < hi:
            raise ValueError(f"winch {name}: start {start} must lie between the buffers {lo} and {hi}")
        if not 0 < v_slow < v_fast:
            raise ValueError(f"winch {name}: need 0 < v_slow < v_fast, got {v_slow}, {v_fast}")
        self.name, self.converter = name, converter
        self.lo, self.hi, self.start = float(lo), float(hi), float(start)
        self.v_fast, self.v_slow, self.f_fast = float(v_fast), float(v_slow), float(f_fast)
        self.f_slow = self.f_fast * self.v_slow / self.v_fast
        self.ramp, self.brake_rate, self.slip = float(ramp_hz_s), float(brake_mm_s2), float(slip)
        self.up, self.down, self.fast, self.slow = up, down, fast, slow
        self.cams = list(cams)
        self.load = 0.0

    # --- the component protocol ------------------------------------------------------------------------------
    def specs(self) -> list[SignalSpec]:
        docs = {
            self.up: "converter: direction up (winds the rope) while True",
            self.down: "converter: direction down while True (both directions: converter fault, brake held)",
            self.slow: f"converter: slow fixed frequency {self.f_slow:g} Hz ({self.v_slow:g} mm/s)",
            self.fast: f"converter: fast fixed frequency {self.f_fast:g} Hz ({self.v_fast:g} mm/s)",
        }
        out = [SignalSpec(a, "actuator", doc=d) for a, d in docs.items()]
        out += [
            SignalSpec(c.name, "sensor", doc=c.doc or f"cam switch: True in [{c.lo:g}, {c.hi:g}] mm") for c in self.cams
        ]
        return out

    def subjects(self) -> set[str]:
        return {self.name, self.converter, "top buffer", "bottom buffer", *(c.name for c in self.cams)}

    def reset(self, host: Host) -> bool:
        self.s, self.v, self.f = self.start, 0.0, 0.0
        self.command = {a: False for a in (self.up, self.down, self.fast, self.slow)}
        self.pending = False
        self.f_set = 0.0
        self.braked = True
        self.fault = False
        self.warning = False
        self.jammed = False
        self.at_end: str | None = None
        self.recheck = False
        for cam in self.cams:
            cam.reset()
            cam.update(self.s)
            host.sensors[cam.name] = cam.actuated
        self._quiet = quiet_range(self.cams, self.s)  # where no cam changes: the cams are read only outside it
        return False

    def actuate(self, host: Host, signal: str, value: Any) -> bool:
        """An output changed: taken with the others of the same scan at the next step."""
        value = bool(value)
        if self.command[signal] != value:
            self.command[signal] = value
            self.pending = True
        return self.pending

    def jam(self, host: Host, jammed: bool = True) -> bool:
        """Fault: the rope is jammed (the carriage stands whatever the command); freed, it moves as commanded."""
        jammed = bool(jammed)
        if jammed and not self.jammed:
            host.emit("motor jammed", self.name, position=round(self.s, 3), commanded=not self.braked)
            self.v = self.f = 0.0
        self.jammed = jammed
        return True

    def shift_cam(self, name: str, dx: float) -> None:
        """Fault: cam ``name`` mounted ``dx`` mm off its place (+ = up the track)."""
        next(c for c in self.cams if c.name == name).shift(dx)
        self.recheck = self.pending = True  # the cams are read again at the next step

    # --- the converter ---------------------------------------------------------------------------------------
    def _take_commands(self, host: Host) -> None:
        """The set point and the brake from the four outputs, with the converter's fault and warning."""
        c = self.command
        up, down = c[self.up], c[self.down]
        fault = up and down
        if fault and not self.fault:
            host.emit("converter fault", self.converter, reason="both directions commanded: 0 Hz, brake held")
        self.fault = fault
        direction = 0 if up == down else (1 if up else -1)
        hz = self.f_fast if c[self.fast] else self.f_slow if c[self.slow] else 0.0
        warning = direction != 0 and hz == 0.0
        if warning and not self.warning:
            host.emit("converter warning", self.converter, reason="a direction without a speed: 0 Hz, brake held")
        self.warning = warning
        self.f_set = direction * hz
        self.braked = self.f_set == 0.0

    def advance(self, host: Host, dt: float) -> bool:
        if self.pending:
            self.pending = False
            self._take_commands(host)
        if self.jammed:
            v = 0.0
        elif self.braked:
            v = self.v - math.copysign(min(abs(self.v), self.brake_rate * dt), self.v)
            self.f = v / self.v_fast * self.f_fast
        else:
            f = self.f
            if f != self.f_set:
                df = self.f_set - f
                step = self.ramp * dt
                self.f = f = self.f_set if abs(df) <= step else f + math.copysign(step, df)
            # the carriage's speed at f with the present load
            v = (
                0.0
                if f == 0.0
                else f / self.f_fast * self.v_fast * (1.0 - self.slip * self.load * math.copysign(1.0, f))
            )
        s = self.s + v * dt
        if s >= self.hi or s <= self.lo:
            end = "top buffer" if s >= self.hi else "bottom buffer"
            s = self.hi if s >= self.hi else self.lo
            if self.at_end != end:
                self.at_end = end
                host.emit("end stop hit", end, speed_mm_s=round(v, 3))
            v = 0.0
        elif self.at_end is not None:
            self.at_end = None
        if s != self.s or self.recheck:
            lo, hi = self._quiet
            if self.recheck or not lo <= s <= hi:
                self.s = s
                for cam in self.cams:
                    if cam.update(s):
                        host.sensors[cam.name] = cam.actuated
                        if cam.actuated:
                            host.emit("speed measured", cam.name, speed_mm_s=round(v, 3), position=round(s, 3))
                self._quiet = quiet_range(self.cams, s)
            self.s, self.recheck = s, False
        self.v = v
        return v != 0.0 or not (self.braked or self.jammed)

    @property
    def busy(self) -> bool:
        return self.v != 0.0 or self.pending or not (self.braked or self.jammed)

    def static_drawables(self) -> list[Drawable]:
        return []

    def dynamic_drawables(self) -> list[Drawable]:
        return []
