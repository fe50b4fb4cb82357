"""SPINDLE: a spindle motor reversed by two contactors with feedback contacts (seed 003, §4.3, CWCCW).

The rig of the PLC836 mechanisms chapter's spindle examples. Contactor ``SMP`` (motor positive, the
spindle clockwise) and ``SMN`` (negative, counter-clockwise) each have an auxiliary contact, ``KSMP`` and
``KSMN``, that follows the coil after a pick-up delay (40 ms) when the coil is switched on and a drop-out
delay (30 ms) when it is switched off. The spindle follows the main contacts: +1000 rpm with SMP's closed,
-1000 rpm with SMN's, a first-order drive (τ = 0.3 s). Both main contacts closed at once short-circuit
the supply (event ``short circuit``; the spindle gets no torque while it lasts): the reason the chapter's
CWCCW waits for KSMP to drop and then 0.2 s more before it switches SMN on.

The operator panel has push-buttons ``START`` (spindle on, clockwise), ``REV`` (reverse) and ``STOP`` and
lamps ``READY`` and ``ALARM``. The chapter's faults: a contact stuck (the scenario's ``stuck("KSMP", True)``
on the wire) and a contactor that never picks up (``jam_motor("SMN")``: its coil is switched, its contacts
stay open).

>>> s = Spindle()
>>> s.actuate("SMP", True)
>>> s.step(39_000_000); s.sensors["KSMP"]
False
>>> s.step(1_000_000); s.sensors["KSMP"], s.events[-1].kind
(True, 'contactor picked up')
"""

from __future__ import annotations

import math
from typing import Any

from plants.components import draw
from plants.components.panel import OperatorPanel
from plcsim.plant import MOTOR_JAM, OBSERVABLES, OPERATOR, QUIESCENCE, Drawable, PlantEvent, RigVerb, SignalSpec

PICK_UP_S, DROP_OUT_S = 0.040, 0.030
RPM, TAU_S = 1000.0, 0.3
CONTACTORS = {"SMP": ("KSMP", 1.0), "SMN": ("KSMN", -1.0)}
"""Coil -> (its feedback contact, the direction it drives the spindle)."""
ORDER = ("START", "REV", "STOP", "KSMP", "KSMN", "SMP", "SMN", "READY", "ALARM")
_NS = 1_000_000_000


class Spindle:
    """The spindle with its two reversing contactors and a panel (see the module docstring)."""

    view = "side"
    CAPABILITIES = frozenset({OPERATOR, QUIESCENCE, OBSERVABLES, MOTOR_JAM})
    VERBS: dict[str, RigVerb] = {}
    EVENTS = OperatorPanel.EVENTS | {"contactor picked up", "contactor dropped out", "short circuit"}

    def __init__(
        self, *, pick_up: float = PICK_UP_S, drop_out: float = DROP_OUT_S, name: str = "SPINDLE", seed: int = 0
    ) -> None:
        self.name = name
        self.pick_up_ns, self.drop_out_ns = round(pick_up * _NS), round(drop_out * _NS)
        self.panel = OperatorPanel(("START", "REV", "STOP"), (), ("READY", "ALARM"), origin=(0.0, 120.0))
        coil_doc = "contactor coil {}: its main and auxiliary contacts close {:g} ms after it is switched on"
        specs = {s.name: s for s in self.panel.specs()}
        for coil, (contact, _) in CONTACTORS.items():
            specs[coil] = SignalSpec(coil, "actuator", doc=coil_doc.format(coil, self.pick_up_ns / 1e6))
            specs[contact] = SignalSpec(
                contact, "sensor", doc=f"auxiliary contact of {coil}: True while closed (follows the coil)"
            )
        self.signals: dict[str, SignalSpec] = {n: specs[n] for n in ORDER}
        self.sensors: dict[str, Any] = {}
        self.events: list[PlantEvent] = []
        self.seed = seed
        self.reset(seed=seed)

    # -- the protocol ---------------------------------------------------------------------------------------
    def reset(self, *, seed: int | None = None) -> None:
        """Coils off, contacts open, the spindle still, no fault, time 0."""
        if seed is not None:
            self.seed = seed
        self.now_ns = 0
        self.events.clear()
        self.sensors.clear()
        self.panel.reset(self)
        self.coils = dict.fromkeys(CONTACTORS, False)
        self.jammed: set[str] = set()
        self.due: dict[str, tuple[int, bool]] = {}
        """Coil -> (when its contacts change, to what)."""
        self.rpm = 0.0
        self.shorted = False
        for contact, _ in CONTACTORS.values():
            self.sensors[contact] = False

    def emit(self, kind: str, subject: str, part: str | None = None, **data: Any) -> None:
        self.events.append(PlantEvent(self.now_ns, kind, subject, part, data))

    def actuate(self, name: str, value: Any) -> None:
        if name in self.panel.lamps:
            self.panel.actuate(self, name, value)
            return
        if name not in CONTACTORS:
            raise KeyError(f"{self.name} has no actuator {name!r} (actuators: SMP, SMN, READY, ALARM)")
        value = bool(value)
        if self.coils[name] == value:
            return
        self.coils[name] = value
        contact = CONTACTORS[name][0]
        if value and name in self.jammed:
            self.due.pop(name, None)
        elif self.sensors[contact] == value:
            self.due.pop(name, None)  # switched back before the contacts moved
        else:
            self.due[name] = (self.now_ns + (self.pick_up_ns if value else self.drop_out_ns), value)

    def operate(self, name: str, value: Any) -> None:
        self.panel.operate(self, name, value)

    def step(self, dt_ns: int) -> None:
        if dt_ns <= 0:
            raise ValueError(f"step: dt_ns must be > 0, not {dt_ns}")
        end = self.now_ns + dt_ns
        while self.due:
            coil, (when, value) = min(self.due.items(), key=lambda item: item[1][0])
            if when > end:
                break
            self._spin(when - self.now_ns)
            self.now_ns = when
            del self.due[coil]
            self.sensors[CONTACTORS[coil][0]] = value
            self.emit("contactor picked up" if value else "contactor dropped out", coil)
            self._check_short()
        self._spin(end - self.now_ns)
        self.now_ns = end

    def _torque(self) -> float:
        closed = [direction for contact, direction in CONTACTORS.values() if self.sensors[contact]]
        return closed[0] if len(closed) == 1 else 0.0

    def _spin(self, dt_ns: int) -> None:
        if dt_ns <= 0:
            return
        target = RPM * self._torque()
        self.rpm = target + (self.rpm - target) * math.exp(-dt_ns / _NS / TAU_S)
        if abs(self.rpm - target) < 0.5:  # settled: within half an rpm
            self.rpm = target

    def _check_short(self) -> None:
        both = all(self.sensors[contact] for contact, _ in CONTACTORS.values())
        if both and not self.shorted:
            self.emit("short circuit", "spindle")
        self.shorted = both

    def quiescent(self) -> bool:
        """True while no contact is about to move and the spindle runs at its speed (or stands)."""
        return not self.due and self.rpm == RPM * self._torque()

    def jam_motor(self, name: str, jammed: bool) -> None:
        """Fault: contactor ``name`` (SMP or SMN) does not pick up; a closed one stays as it is."""
        if name not in CONTACTORS:
            raise KeyError(f"{self.name} has no contactor {name!r} (contactors: SMP, SMN)")
        if jammed:
            self.jammed.add(name)
            if self.due.get(name, (0, False))[1]:
                del self.due[name]
        else:
            self.jammed.discard(name)
            if self.coils[name] and not self.sensors[CONTACTORS[name][0]]:
                self.due[name] = (self.now_ns + self.pick_up_ns, True)

    def event_subjects(self) -> set[str]:
        return set(self.panel.controls) | set(CONTACTORS) | {"spindle"}

    def observables(self) -> dict[str, float]:
        """The spindle's speed in rpm (positive: clockwise)."""
        return {"spindle.rpm": self.rpm}

    # -- drawing --------------------------------------------------------------------------------------------
    def bounds(self) -> tuple[float, float, float, float]:
        return (-10.0, -10.0, 260.0, 180.0)

    def static_drawables(self) -> list[Drawable]:
        out = [draw.label("title", 120.0, 105.0, "spindle reversal: SMP (CW), SMN (CCW)")]
        for k, coil in enumerate(CONTACTORS):
            out.append(draw.label(f"contactors/{coil}/label", 20.0 + 70.0 * k, 90.0, coil))
        return out + self.panel.static_drawables("panel")

    def dynamic_drawables(self) -> list[Drawable]:
        out: list[Drawable] = []
        for k, (coil, (contact, _)) in enumerate(CONTACTORS.items()):
            x = 10.0 + 70.0 * k
            color = draw.LAMP_ON if self.coils[coil] else draw.LAMP_OFF
            out.append(draw.polygon(f"contactors/{coil}/coil", draw.rect(x, 50.0, x + 40.0, 80.0), color, coil))
            state = draw.BEAM_CUT if self.sensors[contact] else draw.BEAM_FREE
            out.append(draw.polygon(f"contactors/{coil}/contact", draw.rect(x, 35.0, x + 40.0, 45.0), state, contact))
        turn = draw.BELT_RUNNING if self.rpm else draw.BELT
        out.append(draw.circle("spindle/body", 200.0, 60.0, 25.0, turn, f"{self.rpm:+.0f} rpm"))
        return out + self.panel.dynamic_drawables("panel")
