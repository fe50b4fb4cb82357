"""An analog colour sensor seen from above: a spot that reads the colour of the part covering it, 0…27648 raw.

The raw value is the part's colour mean (its ``colour_raw`` property, or the rig's table of colour means for its
``colour`` property) plus Gaussian noise (σ ``noise``, drawn from the rig's seeded generator in every step while a
part covers the spot) plus the ambient-light offset (``ambient``, a scenario fault: ``set_ambient``), clipped to the
module range. With no part it reads the bare belt (``bare``). The signal is ``analog`` with ``lo..hi`` = 0…27648, so
the wiring passes the raw value through unscaled.

**Conversion cycle.** An S7-1200 analog input delivers a new value once per conversion cycle, not in every scan:
the reading is held between conversions at the multiples of ``update_s`` (a free-running converter; noise is drawn
once per conversion). The default 5 ms is an inference [I]: the exercise assumes the CPU 1214C's built-in analog
inputs; the S7-1200 system manual gives their sample and update times per noise-rejection (integration time)
selection, and with the 50 Hz rejection a European lab would use (20 ms integration) we take a quarter of it,
5 ms. Neither the textbook (§1.2.3: the speed "depends on the module") nor the spec gives a number. The reading is
computed lazily: the sensor is advanced only while a part covers the spot or a change waits for the next
conversion, and then does work only when the hold expires.

The spot is a sensor shape like :class:`~plants.components.top_view.SpotSensor`: the rig's collision callback calls
:meth:`ColourSensor.enter` / :meth:`ColourSensor.leave`.
"""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import pymunk

from plants.components import draw
from plants.components.component import Host, zone
from plants.components.sketch import Sketch
from plcsim.plant import Drawable, SignalSpec

RAW_MAX = 27_648


class ColourSensor:
    """Analog colour sensor ``name`` with its spot at (x, y)."""

    EVENTS: frozenset[str] = frozenset()

    def __init__(
        self,
        name: str,
        x: float,
        y: float,
        *,
        radius: float = 2.5,
        update_s: float = 0.005,
        colours: Mapping[int, float] | None = None,
        bare: float = 26_500.0,
        noise: float = 500.0,
        doc: str = "",
        label_at: tuple[float, float] | None = None,
    ) -> None:
        self.name, self.x, self.y, self.radius = name, float(x), float(y), float(radius)
        self.label_at = label_at  # where "name reading" is written (default: name under the spot, reading on it)
        self.colours = dict(colours or {})
        self.bare, self.noise = float(bare), float(noise)
        if update_s <= 0:
            raise ValueError(f"colour sensor {name}: the update time must be > 0")
        self.period_ns = round(update_s * 1e9)
        self.doc = doc or f"colour sensor at ({x:g}, {y:g}): raw 0..{RAW_MAX} (σ {noise:g})"
        self._sketch = Sketch(self._draw)

    def specs(self) -> list[SignalSpec]:
        return [SignalSpec(self.name, "sensor", "analog", doc=self.doc, unit="raw", lo=0.0, hi=float(RAW_MAX))]

    def subjects(self) -> set[str]:
        return {self.name}

    def reset(self, host: Host) -> bool:
        self.parts: dict[str, float] = {}  # covering parts -> their colour mean
        self.ambient = 0.0
        zone(host, self, pymunk.Circle(host.space.static_body, self.radius, (self.x, self.y)))
        self.value = host.sensors[self.name] = self._clip(self.bare)
        self._due_ns = 0  # the next conversion that may change the reading
        return False

    def mean_of(self, props: Mapping[str, Any]) -> float:
        """The colour mean of a part with these properties."""
        if "colour_raw" in props:
            return float(props["colour_raw"])
        return float(self.colours[int(props["colour"])])

    def enter(self, host: Host, part: Any) -> None:
        """A part (with ``id`` and ``props``) covers the spot."""
        self.parts[part.id] = self.mean_of(part.props)
        self._changed(host)

    def leave(self, host: Host, pid: str) -> None:
        if self.parts.pop(pid, None) is not None:
            self._changed(host)

    def set_ambient(self, host: Host, offset: float) -> None:
        """Fault / condition: ambient light adds ``offset`` raw units to every reading."""
        self.ambient = float(offset)
        self._changed(host)

    def _changed(self, host: Host) -> None:
        """What the spot sees changed: the first conversion from the next step on shows it."""
        period = self.period_ns
        self._due_ns = max(self._due_ns, -(-(host.now_ns + 1) // period) * period)
        host.wake(self)

    def _clip(self, raw: float) -> int:
        return max(0, min(RAW_MAX, round(raw)))

    def actuate(self, host: Host, signal: str, value: Any) -> bool:
        return False

    def advance(self, host: Host, dt: float) -> bool:
        now = host.now_ns
        if now < self._due_ns:  # the last conversion's value holds
            return True
        self._due_ns = (now // self.period_ns + 1) * self.period_ns
        if self.parts:
            mean = next(iter(self.parts.values()))
            noise = self.noise * host.rng.standard_normal()  # = rng.normal(0, noise) bit for bit, at half the cost
            self.value = host.sensors[self.name] = self._clip(mean + self.ambient + noise)
            return True
        self.value = host.sensors[self.name] = self._clip(self.bare + self.ambient)
        return False

    def static_drawables(self) -> list[Drawable]:
        if self.label_at is not None:
            return []
        return [draw.label(f"sensors/{self.name}/label", self.x, self.y - self.radius - 6.0, self.name)]

    def dynamic_drawables(self) -> list[Drawable]:
        return self._sketch(self.value)

    def _draw(self) -> list[Drawable]:
        grey = int(255 * self.value / RAW_MAX)  # the reading as a grey level: dark = low raw value
        if self.label_at is None:
            return [
                draw.circle(f"sensors/{self.name}", self.x, self.y, self.radius, (grey, grey, grey), str(self.value))
            ]
        return [
            draw.circle(f"sensors/{self.name}", self.x, self.y, self.radius, (grey, grey, grey)),
            draw.label(f"sensors/{self.name}/label", *self.label_at, f"{self.name} {self.value}"),
        ]
