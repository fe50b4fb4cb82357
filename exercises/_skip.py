"""What the skip-hoist exercise (4.3.16) needs beyond the checker's words: the position states a correct program
must show, computed from what the PLC read (its input image) and where the skip went, and the operator's moves."""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from plants.skip import FILL
from plcsim.check import Condition, Context
from plcsim.scenario import after_event, write

DOLNY, SPOMAL, HORNY = "SNIMAC_DOLNY", "SNIMAC_SPOMAL", "SNIMAC_HORNY"
UP, DOWN = "START_HORE", "START_DOLE"
RESTARTS = frozenset({"start_cpu", "power_cycle"})


def positions(ctx: Context) -> tuple[np.ndarray, np.ndarray]:
    """Per scan, POZ1 and POZ2 as the task defines them: POZ1 from the scan in which the skip leaves SNIMAC_DOLNY
    going up, or SNIMAC_SPOMAL going down; POZ2 from leaving SNIMAC_SPOMAL going up, or SNIMAC_HORNY going down;
    both FALSE in every scan in which a sensor reads TRUE, and after a start of the PLC until a sensor is left
    again. The sensors are the input image the program read; the direction is the one the converter was given
    when the sensor was left (the outputs of the scan before: the skip moves only while driven)."""
    trace = ctx.trace
    times = trace.times
    low, mid, top = (trace.column(n).astype(bool) for n in (DOLNY, SPOMAL, HORNY))
    driven_up, driven_down = (trace.column(n).astype(bool) for n in (UP, DOWN))
    starts = sorted(e.t_ns for e in trace.events if e.source == "scenario" and e.kind in RESTARTS)
    poz1 = np.zeros(len(times), dtype=bool)
    poz2 = np.zeros(len(times), dtype=bool)
    p1 = p2 = False
    k_start = 0
    for k in range(len(times)):
        while k_start < len(starts) and starts[k_start] <= times[k]:
            p1 = p2 = False
            k_start += 1
        if k:
            up, down = driven_up[k - 1], driven_down[k - 1]
            if (low[k - 1] and not low[k] and up) or (mid[k - 1] and not mid[k] and down):
                p1 = True
            if (mid[k - 1] and not mid[k] and up) or (top[k - 1] and not top[k] and down):
                p2 = True
        if low[k] or mid[k] or top[k]:
            p1 = p2 = False
        poz1[k], poz2[k] = p1, p2
    return poz1, poz2


@dataclass(frozen=True)
class WrongPosition(Condition):
    """True in the scans in which the program's position state ``tag`` (``DB_SKIP.POZ1`` or ``.POZ2``) differs
    from the one the task defines (:func:`positions`)."""

    tag: str
    which: int

    def rows(self, ctx: Context) -> np.ndarray:
        want = positions(ctx)[self.which - 1]
        return ctx.trace.column(self.tag).astype(bool) != want

    def describe(self) -> str:
        zone = "SNIMAC_DOLNY and SNIMAC_SPOMAL" if self.which == 1 else "SNIMAC_SPOMAL and SNIMAC_HORNY"
        return f"{self.tag} differs from 'the skip is between {zone} after moving there'"

    def signals(self) -> list[str]:
        return [self.tag, DOLNY, SPOMAL, HORNY, UP, DOWN]


def refill() -> list:
    """Back at the bottom, the hopper fills the skip again 1..1.5 s after it arrived; the dosing control reports
    it with PLNY, and the mixer's control, which has taken the first batch, clears KAMENIVO_DODANE."""
    back = after_event("speed measured", DOLNY)
    return [
        FILL("skip", when=back, delay="1s..1.5s"),
        write("DB_MIESACKA.KAMENIVO_DODANE", False, when=back, delay="1.6s..1.7s"),
        write("DB_SKIP.PLNY", True, when=back, delay="1.8s..2.1s"),
    ]


def auto_cycle(mixer_ready: str = "0.5s..0.9s") -> list:
    """The operator selects AUTO, the hopper fills the skip and the dosing control reports it (PLNY), and the
    mixer allows aggregate (KAMENIVO_POVOL) at ``mixer_ready``: one automatic cycle."""
    return [
        write("DB_SKIP.AUTO", True, t="0.1s"),
        FILL("skip", t="0.2s..0.4s"),
        write("DB_SKIP.PLNY", True, t="0.5s..0.7s"),
        write("DB_MIESACKA.KAMENIVO_POVOL", True, t=mixer_ready),
    ]
