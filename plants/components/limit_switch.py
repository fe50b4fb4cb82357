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
