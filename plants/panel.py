"""PANEL: the operator panel of exercises 4.3.1–4.3.4, 4.3.8, 4.3.11, 4.3.13, 4.3.19–4.3.22. No physics.

Buttons and switches are sensors with ``operator=True`` that the scenario sets with :meth:`Panel.operate`; the plant
reports the physical state (True = pressed / switched on) and logs ``button pressed`` / ``button released`` events
(switches too, with ``data={"control": "switch"}``). NO/NC wiring (4.3.2) is the wiring's job. Lamps are actuators.

>>> p = Panel(buttons=("TLACIDLO",), lamps=("LED",))
>>> p.operate("TLACIDLO", True); p.step(1_000_000); p.sensors["TLACIDLO"], p.events[0].kind
(True, 'button pressed')
"""

from __future__ import annotations

from collections.abc import Iterable
from typing import Any

from plants.components.panel import OperatorPanel
from plcsim.plant import OBSERVABLES, OPERATOR, QUIESCENCE, Drawable, PlantEvent, RigVerb, SignalSpec

DEFAULT_BUTTONS = ("TLACIDLO", "TL", "TLACIDLO_ZAP", "TLACIDLO_VYP")
DEFAULT_SWITCHES = ("PREPINAC",)
DEFAULT_LAMPS = ("LED",)


class Panel:
    """A generic operator panel: ``Panel(buttons=..., switches=..., lamps=...)``.

    With no arguments it carries every control the course's panel exercises name: buttons TLACIDLO, TL,
    TLACIDLO_ZAP, TLACIDLO_VYP, switch PREPINAC and lamp LED.
    """

    view = "panel"
    EVENTS = OperatorPanel.EVENTS
    CAPABILITIES = frozenset({OPERATOR, QUIESCENCE, OBSERVABLES})
    VERBS: dict[str, RigVerb] = {}

    def __init__(
        self,
        buttons: Iterable[str] = DEFAULT_BUTTONS,
        switches: Iterable[str] = DEFAULT_SWITCHES,
        lamps: Iterable[str] = DEFAULT_LAMPS,
        *,
        name: str = "PANEL",
        docs: dict[str, str] | None = None,
        seed: int = 0,
    ) -> None:
        self.name = name
        self.panel = OperatorPanel(buttons, switches, lamps, docs=docs)
        self.signals: dict[str, SignalSpec] = {s.name: s for s in self.panel.specs()}
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
        self.panel.reset(self)

    def emit(self, kind: str, subject: str, part: str | None = None, **data: Any) -> None:
        """Record a plant event at the current time (the panel component's events)."""
        self.events.append(PlantEvent(self.now_ns, kind, subject, part, data))

    @property
    def lamps(self) -> dict[str, bool]:
        """{lamp: lit}."""
        return self.panel.lamp_state

    def actuate(self, name: str, value: Any) -> None:
        if name not in self.panel.lamp_state:
            raise KeyError(f"{self.name} has no lamp {name!r} (lamps: {list(self.panel.lamps)})")
        self.panel.actuate(self, name, value)

    def operate(self, name: str, value: Any) -> None:
        self.panel.operate(self, name, value)

    def event_subjects(self) -> set[str]:
        """Its events name the button or switch."""
        return set(self.panel.controls)

    def quiescent(self) -> bool:
        """Always: a panel has no physics; a step only advances its clock."""
        return True

    def step(self, dt_ns: int) -> None:
        if dt_ns <= 0:
            raise ValueError(f"step: dt_ns must be > 0, not {dt_ns}")
        self.now_ns += dt_ns

    def static_drawables(self) -> list[Drawable]:
        return self.panel.static_drawables("panel")

    def dynamic_drawables(self) -> list[Drawable]:
        return self.panel.dynamic_drawables("panel")

    def bounds(self) -> tuple[float, float, float, float]:
        x0, y0, x1, y1 = self.panel.extent()
        return (x0 - 10.0, y0 - 10.0, x1 + 10.0, y1 + 10.0)

    def observables(self) -> dict[str, float]:
        return {f"{n}.lit": float(v) for n, v in self.panel.lamp_state.items()}
