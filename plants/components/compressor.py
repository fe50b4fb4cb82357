"""A compressor and its air reservoir: the pressure builds while it runs and decays when it stops.

The pressure is a fraction ``p`` of full pressure (0…1), first order: ``dp/dt = (1 - p)/tau_up`` while the
compressor runs, ``-p/tau_down`` while it is off (the pistons' consumption and leaks, lumped). §5.8: τ 0.1 s up,
0.5 s down. A piston takes :meth:`Compressor.fraction` as its ``supply`` and moves out only above its threshold
(30 %), so a program that forgets the compressor never ejects anything. ``fail()`` is a fault: the motor runs but
builds no pressure (a broken belt, an open drain valve).

The pressure is not integrated step by step: between two changes (the motor switched, the fault) it is the exact
solution ``p = target + (p0 - target)·exp(-(t - t0)/tau)`` of the time since the change, computed when it is read
(by a piston, by the drawing). The compressor stays busy only until the reservoir has settled (within ``SETTLED``
of its target; off, it is empty from then on), so that the rig is not quiescent while the gauge still moves; its
``advance`` is then one comparison of the clock.

>>> from plants.components.component import Bench
>>> c = Compressor("K", "Kompresor"); host = Bench(); _ = c.reset(host)
>>> _ = c.actuate(host, "Kompresor", True)
>>> for _ in range(36): host.step(c)
>>> round(c.fraction(), 3)  # 1 - exp(-36 ms / 100 ms): above the pistons' 30 % after 36 ms
0.302
>>> _ = c.actuate(host, "Kompresor", False)
>>> for _ in range(500): host.step(c)
>>> round(c.fraction(), 3)  # 0.302 · exp(-0.5 s / 0.5 s)
0.111
"""

from __future__ import annotations

import math
from typing import Any

from plants.components import draw
from plants.components.component import Host
from plants.components.sketch import Sketch
from plcsim.plant import Drawable, SignalSpec

SETTLED = 1e-4  # below this pressure (or this close to full) the reservoir counts as settled


class Compressor:
    """Compressor ``actuator`` feeding a reservoir; ``fraction()`` is the pressure for the pistons."""

    EVENTS = frozenset({"compressor failed"})

    def __init__(
        self,
        name: str,
        actuator: str,
        *,
        tau_up_s: float = 0.1,
        tau_down_s: float = 0.5,
        at: tuple[float, float] = (0.0, 0.0),
        doc: str = "",
        label_at: tuple[float, float] | None = None,
    ) -> None:
        if tau_up_s <= 0 or tau_down_s <= 0:
            raise ValueError(f"compressor {name}: time constants must be > 0")
        self.name, self.actuator = name, actuator
        self.tau_up, self.tau_down = float(tau_up_s), float(tau_down_s)
        self.at = at
        self.label_at = label_at  # where the name is written (default: under the symbol)
        self.doc = doc or f"compressor {name}: builds pressure while True (τ {tau_up_s:g} s; decays τ {tau_down_s:g} s)"
        self._sketch = Sketch(self._draw)

    def specs(self) -> list[SignalSpec]:
        return [SignalSpec(self.actuator, "actuator", doc=self.doc)]

    def subjects(self) -> set[str]:
        return {self.name}

    def reset(self, host: Host) -> bool:
        self._host = host  # its clock: the pressure is read as a function of time
        self.on = False
        self.failed = False
        # since t0 (ns) the pressure goes from p0 toward target with time constant tau (s); settled from settled_ns
        self._p0, self._t0, self._target, self._tau, self._settled_ns = 0.0, 0, 0.0, self.tau_down, 0
        return False

    def fraction(self) -> float:
        """The pressure now, as a fraction of full pressure."""
        now = self._host.now_ns
        if self._target == 0.0 and now >= self._settled_ns:
            return 0.0
        return self._target + (self._p0 - self._target) * math.exp((self._t0 - now) / 1e9 / self._tau)

    def _change(self, host: Host) -> bool:
        """The motor or the fault changed: the pressure now starts toward its new target; True while unsettled."""
        p, now = self.fraction(), host.now_ns
        building = self.on and not self.failed
        self._target, self._tau = (1.0, self.tau_up) if building else (0.0, self.tau_down)
        self._p0, self._t0 = p, now
        gap = abs(self._target - p)
        self._settled_ns = now + (math.ceil(self._tau * math.log(gap / SETTLED) * 1e9) if gap > SETTLED else 0)
        return self._settled_ns > now

    def actuate(self, host: Host, signal: str, value: Any) -> bool:
        if bool(value) == self.on:
            return False
        self.on = bool(value)
        return self._change(host)

    def fail(self, host: Host, failed: bool = True) -> bool:
        """Fault: it runs but builds no pressure."""
        if failed and not self.failed:
            host.emit("compressor failed", self.name)
        self.failed = bool(failed)
        return self._change(host)

    def advance(self, host: Host, dt: float) -> bool:
        return host.now_ns < self._settled_ns

    def static_drawables(self) -> list[Drawable]:
        x, y = self.label_at or (self.at[0], self.at[1] - 14.0)
        return [draw.label(f"compressor/{self.name}/label", x, y, self.name)]

    def dynamic_drawables(self) -> list[Drawable]:
        return self._sketch((self.on, self.fraction()))

    def _draw(self) -> list[Drawable]:
        x, y = self.at
        p = self.fraction()
        gauge = [(x - 10.0, y), (x - 10.0 + 20.0 * p, y), (x - 10.0 + 20.0 * p, y + 6.0), (x - 10.0, y + 6.0)]
        out = [draw.circle(f"compressor/{self.name}", x, y - 6.0, 6.0, draw.LAMP_ON if self.on else draw.LAMP_OFF)]
        if p > 0.0:
            out.append(draw.polygon(f"compressor/{self.name}/pressure", gauge, draw.BELT_RUNNING))
        return out
