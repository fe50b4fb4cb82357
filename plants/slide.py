"""SLIDE (the Tecomat manual's EX-19): a hydraulic feed slide ("suport") between the limit switches k1..k5.

The manual's task: "After START1 and START2 are pressed together, one working cycle is executed, which can be
stopped at any time by the STOP button. At limit switch K5 the slide waits 5 s. A new start is possible only from
the initial position (K1). The hydraulic motor is controlled by the solenoid valves EM1, EM2, EM3: EM1 forward
motion, EM2 backward motion, EM3 speed control." Its figure is lost; the labels left are "Hydraul. motor",
"suport", "K1 K2 K3 K4 K5", "Rychloposuv" (rapid traverse). What this rig chooses where the figure is gone:

* the slide is a kinematic :class:`~plants.components.axis.Axis` over a 200 mm stroke, first-order drive
  τ = 50 ms: ``em1`` drives it forward (toward k5), ``em2`` backward (toward k1), both at once stop it
  (``interlock violated``); it moves at the working feed, 40 mm/s, or at the rapid traverse, 120 mm/s, while
  ``em3`` is on;
* the limit switches are 3 mm cams: ``k1`` the initial position (0..3 mm, where the slide rests), ``k2``, ``k3``,
  ``k4`` at 50, 100 and 150 mm (for a program that switches the speed on the way), ``k5`` the end of the working
  stroke (197..200 mm); mechanical end stops 3 mm beyond k1 and k5, where a driven slide stalls (``axis stalled``);
* the two-hand start ``start1``, ``start2`` and ``stop`` are push-buttons on a panel beside it.

The names are the manual's listing's (lower case, as its ``#def`` spells them), and a bare-rig run wires them
to its addresses: start1 X0.0, start2 X0.1, k1 X0.2, k5 X0.3 (k2, k3, k4, stop X0.4..X0.7), em1 Y0.0, em2 Y0.1,
em3 Y0.2, so ``plcsim run SLIDE --program examples/tecomat/ex19_feed_slide.il`` runs EX-19 as printed.

>>> s = Slide()
>>> s.sensors["k1"], s.sensors["k5"]
(True, False)
>>> s.actuate("em1", True)
>>> while not s.sensors["k5"]:
...     s.step(1_000_000)
>>> round(s.now_ns / 1e9, 2)  # from 1.5 mm to k5 (197 mm) at 40 mm/s, + the 50 ms lag of the drive
4.94
"""

from __future__ import annotations

from typing import Any

import numpy as np

from plants.components import draw
from plants.components.axis import Axis
from plants.components.component import Assembly, Host
from plants.components.limit_switch import LimitSwitch
from plants.components.panel import OperatorPanel
from plcsim.plant import (
    MOTOR_JAM,
    OBSERVABLES,
    OPERATOR,
    QUIESCENCE,
    SENSOR_SHIFT,
    Drawable,
    PlantEvent,
    RigVerb,
    SignalSpec,
)

STROKE = 200.0
FEED, RAPID = 40.0, 120.0  # mm/s
CAMS = {"k1": 0.0, "k5": STROKE - 3.0, "k2": 50.0, "k3": 100.0, "k4": 150.0}
"""Each cam's lower edge (3 mm long), in the order of the manual's addresses (k1 X0.2, k5 X0.3)."""
BED_Y, SLIDE_X0, SLIDE_LENGTH = 20.0, 90.0, 60.0  # drawing: the bed's top, the slide's front at s = 0, its length
ORDER = ("start1", "start2", "k1", "k5", "k2", "k3", "k4", "stop", "em1", "em2", "em3")
"""The signals in the order a bare-rig run numbers them (sensors X0.0.., actuators Y0.0..)."""


class FeedSlide(Axis):
    """The slide's axis with a second speed: ``rapid`` while the valve ``rapid_valve`` is on, else ``feed``."""

    def __init__(
        self, name: str, lo: float, hi: float, *, feed: float, rapid: float, rapid_valve: str, **axis: Any
    ) -> None:
        super().__init__(name, lo, hi, speed=feed, **axis)
        self.feed, self.rapid, self.rapid_valve = float(feed), float(rapid), rapid_valve

    def specs(self) -> list[SignalSpec]:
        doc = f"rapid traverse: {self.rapid:g} mm/s instead of the working feed {self.feed:g} mm/s while True"
        return [*super().specs(), SignalSpec(self.rapid_valve, "actuator", doc=doc)]

    def reset(self, host: Host) -> bool:
        self.speed = self.feed
        return super().reset(host)

    def actuate(self, host: Host, signal: str, value: Any) -> bool:
        if signal != self.rapid_valve:
            return super().actuate(host, signal, value)
        self.speed = self.rapid if value else self.feed
        return self.direction != 0


class Slide:
    """The feed slide of EX-19 with its panel (see the module docstring)."""

    view = "side"
    CAPABILITIES = frozenset({OPERATOR, QUIESCENCE, OBSERVABLES, MOTOR_JAM, SENSOR_SHIFT})
    VERBS: dict[str, RigVerb] = {}

    def __init__(self, *, name: str = "SLIDE", seed: int = 0) -> None:
        self.name = name
        cams = [
            LimitSwitch(k, lo, lo + 3.0, doc=f"limit switch {k.upper()}: True in [{lo:g}, {lo + 3:g}] mm")
            for k, lo in CAMS.items()
        ]
        self.slide = FeedSlide(
            "suport",
            -3.0,
            STROKE + 3.0,
            start=1.5,
            feed=FEED,
            rapid=RAPID,
            rapid_valve="em3",
            tau_s=0.05,
            plus="em1",
            minus="em2",
            cams=cams,
            docs={
                "em1": "valve EM1: the slide forward (toward k5) while True",
                "em2": "valve EM2: backward (toward k1)",
            },
            drawing=(SLIDE_X0, BED_Y + 15.0, 1.0, 0.0, 30.0, SLIDE_LENGTH),
        )
        self.assembly = Assembly([self.slide])
        self.panel = OperatorPanel(("start1", "start2", "stop"), (), (), origin=(SLIDE_X0 + STROKE + 60.0, 0.0))
        specs = {s.name: s for s in [*self.panel.specs(), *self.assembly.specs()]}
        self.signals: dict[str, SignalSpec] = {n: specs[n] for n in ORDER}
        self.EVENTS = self.panel.EVENTS | self.assembly.events
        self.space: Any = None
        self.sensors: dict[str, Any] = {}
        self.events: list[PlantEvent] = []
        self.seed = seed
        self.reset(seed=seed)

    # -- the protocol ---------------------------------------------------------------------------------------
    def reset(self, *, seed: int | None = None) -> None:
        """The slide at rest in k1, the valves closed, no fault, time 0."""
        if seed is not None:
            self.seed = seed
        self.rng = np.random.default_rng(self.seed)
        self.now_ns = 0
        self.events.clear()
        self.sensors.clear()
        self.panel.reset(self)
        self.assembly.reset(self)

    def emit(self, kind: str, subject: str, part: str | None = None, **data: Any) -> None:
        self.events.append(PlantEvent(self.now_ns, kind, subject, part, data))

    def wake(self, component: Any) -> None:
        self.assembly.wake(component)

    def actuate(self, name: str, value: Any) -> None:
        if not self.assembly.owns(name):
            raise KeyError(f"{self.name} has no actuator {name!r} (actuators: em1, em2, em3)")
        self.assembly.actuate(self, name, value)

    def operate(self, name: str, value: Any) -> None:
        self.panel.operate(self, name, value)

    def step(self, dt_ns: int) -> None:
        if dt_ns <= 0:
            raise ValueError(f"step: dt_ns must be > 0, not {dt_ns}")
        self.now_ns += dt_ns
        if self.assembly.busy:
            self.assembly.advance(self, dt_ns / 1e9)

    def quiescent(self) -> bool:
        """True while the slide stands still (no valve open)."""
        return not self.assembly.busy

    def jam_motor(self, name: str, jammed: bool) -> None:
        """Fault: the hydraulic motor (``suport`` or one of its valves) does not move the slide."""
        self.assembly.jam(self, name, jammed)

    def shift_sensor(self, name: str, dx_mm: float) -> None:
        """Fault: a limit switch mounted ``dx_mm`` off its place."""
        self.assembly.shift(self, name, dx_mm)

    def event_subjects(self) -> set[str]:
        return set(self.panel.controls) | self.assembly.subjects()

    def observables(self) -> dict[str, float]:
        """The slide's position (mm from k1's edge) and speed (mm/s)."""
        return {"suport.s": self.slide.s, "suport.v": self.slide.v}

    # -- drawing --------------------------------------------------------------------------------------------
    def bounds(self) -> tuple[float, float, float, float]:
        _, y0, x1, y1 = self.panel.extent()
        return (-10.0, min(-10.0, y0 - 10.0), x1 + 10.0, max(120.0, y1 + 10.0))

    def static_drawables(self) -> list[Drawable]:
        bed = draw.polygon("bed", draw.rect(0.0, 0.0, SLIDE_X0 + STROKE + 10.0, BED_Y), draw.FRAME, "bed")
        motor = draw.polygon("motor", draw.rect(0.0, BED_Y, 20.0, BED_Y + 30.0), draw.BELT, "hydraulic motor")
        # each cam's name above its lamp: a name hangs below its point, and would cover the lamp
        labels = [draw.label(f"cams/{k}", SLIDE_X0 + lo, BED_Y + 70.0, k.upper()) for k, lo in CAMS.items()]
        # the motor's name above it, left of K1's: on the motor it would cover the slide's name and the rod
        labels.append(draw.label("motor/label", 35.0, BED_Y + 80.0, "hydraulic motor"))
        return [bed, motor, *labels, *self.panel.static_drawables("panel")]

    def dynamic_drawables(self) -> list[Drawable]:
        cams = [
            draw.polygon(
                f"cams/{k}/state",
                draw.rect(SLIDE_X0 + lo - 1.0, BED_Y + 45.0, SLIDE_X0 + lo + 4.0, BED_Y + 49.0),
                draw.BEAM_CUT if self.sensors[k] else draw.BEAM_FREE,
            )
            for k, lo in CAMS.items()
        ]
        rear = SLIDE_X0 + self.slide.s - SLIDE_LENGTH
        rod = draw.line(
            "rod", [(20.0, BED_Y + 15.0), (rear, BED_Y + 15.0)], draw.BELT
        )  # unnamed: too short to write on
        return [rod, *self.assembly.dynamic_drawables(), *cams, *self.panel.dynamic_drawables("panel")]
