"""A compressor and its air reservoir: the pressure builds while it runs and decays when it stops.

The pressure is a fraction ``p`` of full pressure (0…1), first order: ``dp/dt = (1 - p)/tau_up`` while the
compressor runs, ``-p/tau_down`` while it is off (the pistons' consumption and leaks, lumped). §5.8: τ 0.1 s up,
0.5 s down. A piston takes :meth:`Compressor.fraction` as its ``supply`` and moves out only above its threshold
(30 %), so a program that forgets the compressor never ejects anything. ``fail()`` is a fault: the motor runs but
builds no pressure (a broken belt, an open drain valve).

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
        self._decay: tuple[float, float, float] = (-1.0, 0.0, 0.0)
        self._sketch = Sketch(self._draw)

    def specs(self) -> list[SignalSpec]:
        return [SignalSpec(self.actuator, "actuator", doc=self.doc)]

    def subjects(self) -> set[str]:
        return {self.name}

    def reset(self, host: Host) -> bool:
        self.on = False
        self.failed = False
        self.p = 0.0
        return False

    def fraction(self) -> float:
        """The pressure now, as a fraction of full pressure."""
        return self.p

    def actuate(self, host: Host, signal: str, value: Any) -> bool:
        self.on = bool(value)
        return True

    def fail(self, host: Host, failed: bool = True) -> bool:
        """Fault: it runs but builds no pressure."""
        if failed and not self.failed:
            host.emit("compressor failed", self.name)
        self.failed = bool(failed)
        return True

    def advance(self, host: Host, dt: float) -> bool:
        if self._decay[0] != dt:
            self._decay = (dt, math.exp(-dt / self.tau_up), math.exp(-dt / self.tau_down))
        if self.on and not self.failed:
            self.p = 1.0 - (1.0 - self.p) * self._decay[1]
            return 1.0 - self.p > SETTLED
        self.p *= self._decay[2]
        if self.p < SETTLED:
            self.p = 0.0
        return self.p > 0.0

    def static_drawables(self) -> list[Drawable]:
        x, y = self.label_at or (self.at[0], self.at[1] - 14.0)
        return [draw.label(f"compressor/{self.name}/label", x, y, self.name)]

    def dynamic_drawables(self) -> list[Drawable]:
        return self._sketch((self.on, self.p))

    def _draw(self) -> list[Drawable]:
        x, y = self.at
        gauge = [(x - 10.0, y), (x - 10.0 + 20.0 * self.p, y), (x - 10.0 + 20.0 * self.p, y + 6.0), (x - 10.0, y + 6.0)]
        out = [draw.circle(f"compressor/{self.name}", x, y - 6.0, 6.0, draw.LAMP_ON if self.on else draw.LAMP_OFF)]
        if self.p > 0.0:
            out.append(draw.polygon(f"compressor/{self.name}/pressure", gauge, draw.BELT_RUNNING))
        return out
