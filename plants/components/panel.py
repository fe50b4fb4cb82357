"""Operator panel: push-buttons, switches and lamps. No physics.

Buttons and switches are **sensors** driven by the operator (``SignalSpec.operator = True``): the plant reports
``True`` while a button is pressed or a switch is on, and the wiring decides whether the PLC sees that as an NO or an
NC contact. Lamps (LEDs, signal lamps) are actuators. The component keeps the states and produces the events
(``button pressed`` / ``button released``; a switch uses the same kinds with ``data={"control": "switch"}``); a rig
embeds it and shares its ``sensors`` dict and event list.
"""

from __future__ import annotations

from collections.abc import Iterable

from plants.components import draw
from plcsim.plant import Drawable, PlantEvent, SignalSpec


class OperatorPanel:
    """Buttons, switches and lamps laid out in a row from ``origin`` (mm), 50 mm apart."""

    EVENTS = frozenset({"button pressed", "button released"})

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
        self.lamp_state: dict[str, bool] = {}
        self.reset()

    @property
    def controls(self) -> tuple[str, ...]:
        return self.buttons + self.switches

    def reset(self) -> None:
        self.lamp_state = dict.fromkeys(self.lamps, False)

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

    def operate(self, name: str, value, sensors: dict, events: list, now_ns: int) -> None:
        """The operator sets a button or switch; an event is logged when its state changes."""
        if name not in self.controls:
            if name in self.lamps:
                raise ValueError(f"{name} is a lamp (an actuator), the operator cannot set it")
            raise KeyError(f"no button or switch {name!r} on this panel (have {list(self.controls)})")
        value = bool(value)
        if sensors[name] == value:
            return
        sensors[name] = value
        data = {"control": "switch"} if name in self.switches else {}
        events.append(PlantEvent(now_ns, "button pressed" if value else "button released", name, None, data))

    def set_lamp(self, name: str, value) -> None:
        self.lamp_state[name] = bool(value)

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

    def dynamic_drawables(self, sensors: dict, prefix: str = "panel") -> list[Drawable]:
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
