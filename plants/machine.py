"""MACHINE (4.3.13): "a machine without feedback" — one output STROJ_ZAP, drawn as a drilling spindle with a lamp.

No sensors. The plant accumulates the ON time (integer ns, counted per physics step in which STROJ_ZAP was on: a
command applies from the next step on, as for every plant) and counts the switch-ons, so a check can ask "three
pulses of 1 s" from the plant side too (``on_time_ns``, ``starts``, ``observables()``).

>>> m = Machine()
>>> m.actuate("STROJ_ZAP", True)
>>> for _ in range(1500): m.step(1_000_000)
>>> m.actuate("STROJ_ZAP", False); m.step(1_000_000)
>>> m.on_time_ns, m.starts
(1500000000, 1)
"""

from __future__ import annotations

import math
from typing import Any

from plants.components import draw
from plcsim.plant import OBSERVABLES, QUIESCENCE, Drawable, PlantEvent, RigVerb, SignalSpec

SPINDLE_RPM = 120.0  # drawn rotation while on (one turn per 0.5 s)


class Machine:
    """One actuator ``STROJ_ZAP`` (spindle / lamp), no feedback; records the accumulated ON time."""

    view = "side"
    EVENTS: frozenset[str] = frozenset()  # no sensors, no parts: nothing happens that a check could see
    CAPABILITIES = frozenset({QUIESCENCE, OBSERVABLES})
    VERBS: dict[str, RigVerb] = {}

    def __init__(self, *, name: str = "MACHINE", actuator: str = "STROJ_ZAP", seed: int = 0) -> None:
        self.name = name
        self.actuator = actuator
        self.signals: dict[str, SignalSpec] = {
            actuator: SignalSpec(actuator, "actuator", doc="machine (spindle) on while True; no running feedback"),
        }
        self.sensors: dict[str, Any] = {}
        self.events: list[PlantEvent] = []
        self.seed = seed
        self.reset(seed=seed)

    def reset(self, *, seed: int | None = None) -> None:
        if seed is not None:
            self.seed = seed
        self.now_ns = 0
        self.events.clear()
        self.sensors.clear()
        self.on = False
        self.on_time_ns = 0
        self.starts = 0

    @property
    def on_time_s(self) -> float:
        return self.on_time_ns / 1e9

    def actuate(self, name: str, value: Any) -> None:
        if name != self.actuator:
            raise KeyError(f"{self.name} has no actuator {name!r} (it has {self.actuator!r})")
        value = bool(value)
        if value and not self.on:
            self.starts += 1
        self.on = value

    def event_subjects(self) -> set[str]:
        return set()

    def quiescent(self) -> bool:
        """Always: a step only adds time (and ON time), so any number of steps may be taken at once."""
        return True

    def step(self, dt_ns: int) -> None:
        if dt_ns <= 0:
            raise ValueError(f"step: dt_ns must be > 0, not {dt_ns}")
        self.now_ns += dt_ns
        if self.on:
            self.on_time_ns += dt_ns

    def observables(self) -> dict[str, float]:
        return {"on_time_s": self.on_time_s, "starts": float(self.starts)}

    def bounds(self) -> tuple[float, float, float, float]:
        return (-10.0, -10.0, 130.0, 170.0)

    def static_drawables(self) -> list[Drawable]:
        return [
            draw.polygon("machine/table", draw.rect(0.0, 0.0, 120.0, 10.0), draw.FRAME),
            draw.polygon("machine/column", draw.rect(90.0, 10.0, 105.0, 150.0), draw.FRAME),
            draw.polygon("machine/head", draw.rect(40.0, 110.0, 105.0, 140.0), draw.BELT, self.actuator),
            draw.label("machine/label", 60.0, 155.0, self.name),
        ]

    def dynamic_drawables(self) -> list[Drawable]:
        # the spindle seen from the side: a drill whose flute marks advance with the ON time
        turns = self.on_time_ns / 1e9 * SPINDLE_RPM / 60.0
        phase = (turns % 1.0) * 2 * math.pi
        flute_y = [60.0 + 8.0 * k + 4.0 * math.sin(phase) for k in range(5)]
        flutes = [(55.0 + 5.0 * (k % 2 * 2 - 1), y) for k, y in enumerate(flute_y)]
        lamp = draw.LAMP_ON if self.on else draw.LAMP_OFF
        return [
            draw.polygon("machine/spindle", draw.rect(50.0, 60.0, 60.0, 110.0), (200, 200, 210)),
            draw.line("machine/spindle/flutes", flutes, draw.TEXT),
            draw.circle("machine/lamp", 20.0, 125.0, 8.0, lamp, "ON" if self.on else "OFF"),
        ]
