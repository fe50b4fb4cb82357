"""Operator panel: push-buttons, switches and lamps. No physics. A component (:mod:`plants.components.component`).

Buttons and switches are **sensors** driven by the operator (``SignalSpec.operator = True``): the plant reports
``True`` while a button is pressed or a switch is on, and the wiring decides whether the PLC sees that as an NO or an
NC contact. Lamps (LEDs, signal lamps) are actuators. The component keeps the states and produces the events
(``button pressed`` / ``button released``; a switch uses the same kinds with ``data={"control": "switch"}``) in the
rig that hosts it; it declares the :data:`~plcsim.plant.OPERATOR` capability for that rig.
"""

from __future__ import annotations

from collections.abc import Iterable
from typing import Any

from plants.components import draw
from plants.components.component import Host
from plcsim.plant import OPERATOR, Drawable, SignalSpec


class OperatorPanel:
    """Buttons, switches and lamps laid out in a row from ``origin`` (mm), 50 mm apart."""

    EVENTS = frozenset({"button pressed", "button released"})
    CAPABILITIES = frozenset({OPERATOR})
    """What it adds to the rig it is part of."""
    name = "panel"

    def __init__(
        self,
        buttons: Iterable[str] = (),
        switches: Iterable[str] = (),
        lamps: Iterable[str] = (),
        *,
        origin: tuple[float, float] = (0.0, 0.0),
        pitch: float = 50.0,
        lamp_colors: dict[str, tuple[int, int, int]] | None = None,
        docs: dict[str, str] | None = None,
    ) -> None:
        self.buttons = tuple(buttons)
        self.switches = tuple(switches)
        self.lamps = tuple(lamps)
        names = self.buttons + self.switches + self.lamps
        dup = sorted({n for n in names if names.count(n) > 1})
        if dup:
            raise ValueError(f"panel: duplicate names {dup}")
        self.origin = origin
        self.pitch = float(pitch)
        self.lamp_colors = dict(lamp_colors or {})
        self.docs = dict(docs or {})
        self.lamp_state: dict[str, bool] = dict.fromkeys(self.lamps, False)
        self._sensors: dict[str, Any] = self.initial_sensors()

    @property
    def controls(self) -> tuple[str, ...]:
        return self.buttons + self.switches

    # --- the component protocol --------------------------------------------------------------------------------
    def subjects(self) -> set[str]:
        """Its events name the button or switch."""
        return set(self.controls)

    def reset(self, host: Host) -> bool:
        """Every control released, every lamp dark."""
        self.lamp_state = dict.fromkeys(self.lamps, False)
        self._sensors = host.sensors
        host.sensors.update(self.initial_sensors())
        return False

    def actuate(self, host: Host, signal: str, value: Any) -> bool:
        """A lamp is switched."""
        self.lamp_state[signal] = bool(value)
        return False

    def advance(self, host: Host, dt: float) -> bool:
        return False

    def specs(self) -> list[SignalSpec]:
        out = []
        for n in self.buttons:
            out.append(SignalSpec(n, "sensor", doc=self.docs.get(n, "push-button: True while pressed"), operator=True))
        for n in self.switches:
            out.append(SignalSpec(n, "sensor", doc=self.docs.get(n, "switch: True while switched on"), operator=True))
        for n in self.lamps:
            out.append(SignalSpec(n, "actuator", doc=self.docs.get(n, "signal lamp / LED: lit while True")))
        return out

    def initial_sensors(self) -> dict[str, bool]:
        return dict.fromkeys(self.controls, False)

    def operate(self, host: Host, name: str, value: Any) -> None:
        """The operator sets a button or switch; an event is logged when its state changes."""
        if name not in self.controls:
            if name in self.lamps:
                raise ValueError(f"{name} is a lamp (an actuator), the operator cannot set it")
            raise KeyError(f"no button or switch {name!r} on this panel (have {list(self.controls)})")
        value = bool(value)
        if host.sensors[name] == value:
            return
        host.sensors[name] = value
        data = {"control": "switch"} if name in self.switches else {}
        host.emit("button pressed" if value else "button released", name, None, **data)

    # --- drawing ---------------------------------------------------------------------------------------------
    def _slot(self, i: int) -> tuple[float, float]:
        return (self.origin[0] + 25.0 + i * self.pitch, self.origin[1] + 25.0)

    def extent(self) -> tuple[float, float, float, float]:
        n = max(1, len(self.controls) + len(self.lamps))
        x0, y0 = self.origin
        return (x0, y0 - 5.0, x0 + n * self.pitch, y0 + 50.0)

    def static_drawables(self, prefix: str = "panel") -> list[Drawable]:
        out: list[Drawable] = []
        x0, y0, x1, y1 = self.extent()
        out.append(draw.polygon(f"{prefix}/plate", draw.rect(x0, y0, x1, y1), (225, 225, 228)))
        for i, n in enumerate(self.controls + self.lamps):
            x, y = self._slot(i)
            out.append(draw.label(f"{prefix}/labels/{n}", x, y - 20.0, n))
        return out

    def dynamic_drawables(self, prefix: str = "panel") -> list[Drawable]:
        sensors = self._sensors
        out: list[Drawable] = []
        i = 0
        for n in self.buttons:
            x, y = self._slot(i)
            on = sensors[n]
            out.append(
                draw.circle(
                    f"{prefix}/buttons/{n}", x, y, 9.0 if on else 10.0, draw.BUTTON_PRESSED if on else draw.BUTTON, n
                )
            )
            i += 1
        for n in self.switches:
            x, y = self._slot(i)
            on = sensors[n]
            out.append(draw.polygon(f"{prefix}/switches/{n}", draw.rect(x - 8, y - 8, x + 8, y + 8), draw.FRAME, n))
            tip = (x + 7.0, y + 7.0) if on else (x - 7.0, y + 7.0)
            out.append(draw.line(f"{prefix}/switches/{n}/lever", [(x, y), tip], draw.TEXT, "on" if on else "off"))
            i += 1
        for n in self.lamps:
            x, y = self._slot(i)
            on = self.lamp_state[n]
            out.append(
                draw.circle(
                    f"{prefix}/lamps/{n}", x, y, 10.0, self.lamp_colors.get(n, draw.LAMP_ON) if on else draw.LAMP_OFF, n
                )
            )
            i += 1
        return out
