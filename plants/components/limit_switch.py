"""A contact / limit switch: actuated inside a zone of finite length, with hysteresis.

It has no physics of its own: the rig that owns it calls :meth:`LimitSwitch.update` with the position of whatever
actuates it (a cam on a carriage, a piston rod) when that position changes. The switch turns on when the position
enters ``[lo, hi]`` and turns off only when it leaves ``[lo - hysteresis, hi + hysteresis]`` (0.5 mm by default), so a
position that dithers on the zone's edge does not chatter. Contact bounce is the wiring's business.

>>> sw = LimitSwitch("KS1", 10.0, 12.0)
>>> [sw.update(p) for p in (9.0, 10.0, 9.8, 9.4, 11.0, 12.4, 12.6)]
[False, True, False, True, True, False, True]
>>> sw.actuated
False
"""

from __future__ import annotations

import math
from collections.abc import Sequence


class LimitSwitch:
    """Zone ``[lo, hi]`` (mm, along whatever axis the rig uses) with ``hysteresis`` mm on both sides.

    :meth:`update` returns True when the state changed; :attr:`actuated` is the state.
    """

    def __init__(self, name: str, lo: float, hi: float, *, hysteresis: float = 0.5, doc: str = "") -> None:
        if hi < lo:
            raise ValueError(f"limit switch {name}: hi {hi} < lo {lo}")
        if hysteresis < 0:
            raise ValueError(f"limit switch {name}: hysteresis must be >= 0")
        self.name = name
        self.lo = float(lo)
        self.hi = float(hi)
        self.hysteresis = float(hysteresis)
        self.doc = doc
        self.reset()

    def reset(self) -> None:
        self.actuated = False
        self.dx = 0.0  # fault: the switch is mounted dx mm off its nominal place

    def shift(self, dx: float) -> None:
        """Fault: misaligned switch (the zone moves by ``dx`` from its nominal place)."""
        self.dx = float(dx)

    def update(self, pos: float) -> bool:
        """New position of the actuating cam; returns True if the switch changed state."""
        lo, hi = self.lo + self.dx, self.hi + self.dx
        if self.actuated:
            h = self.hysteresis
            new = lo - h <= pos <= hi + h
        else:
            new = lo <= pos <= hi
        if new != self.actuated:
            self.actuated = new
            return True
        return False


def quiet_range(switches: Sequence[LimitSwitch], pos: float) -> tuple[float, float]:
    """The positions ``[lo, hi]`` around ``pos`` at which none of ``switches`` changes state (as :meth:`update`
    decides it, each switch's state being the one it took at ``pos``): a carriage that moves updates its switches
    only when it leaves this range, so a stroke costs two updates per switch instead of one per step.

    >>> sw = [LimitSwitch("A", 10.0, 12.0), LimitSwitch("B", 20.0, 22.0)]
    >>> [s.update(11.0) for s in sw], quiet_range(sw, 11.0)
    ([True, False], (9.5, 12.5))
    >>> [s.update(15.0) for s in sw], quiet_range(sw, 15.0)
    ([True, False], (12.000000000000002, 19.999999999999996))
    """
    lo, hi = -math.inf, math.inf
    for sw in switches:
        a, b = sw.lo + sw.dx, sw.hi + sw.dx
        if sw.actuated:  # stays on while a - h <= pos <= b + h
            lo, hi = max(lo, a - sw.hysteresis), min(hi, b + sw.hysteresis)
        elif pos < a:  # stays off while pos < a
            hi = min(hi, math.nextafter(a, -math.inf))
        else:  # pos > b: stays off while pos > b
            lo = max(lo, math.nextafter(b, math.inf))
    return lo, hi
