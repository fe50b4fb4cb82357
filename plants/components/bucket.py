"""A tipping bucket on a curved track top, and the bulk load it pours into a bin below (a skip into a mixer).

The bucket's tilt follows the carriage's position ``s`` on the track: 0° below ``tip_from``, rising linearly to
``tilt_max`` at ``tip_to`` (the curved top rails turn it over). The load is a **mass flow**, not particles: it
pours once the tilt passes ``pour_from`` and at the full rate ``rate_g_s`` from ``pour_full`` on (linear between),
until the bucket is empty, and all of it falls into the bin (the bin's mouth lies under the whole pouring arc).

One **pour** runs from the first gram out to the moment the flow stops — the bucket empty, or tilted back below
``pour_from`` as the carriage leaves the top — and is reported by ``pour ended`` (subject: the bin) with what it
delivered: ``batch_g`` (the load when it began), ``poured_g`` and ``fraction`` (poured / batch), ``left_g`` (what
stayed in the bucket). The flow is integrated per step (exactly where it runs at the full rate).

>>> from plants.components.component import Bench
>>> b = Bucket("skip", "mixer", tip_from=900.0, tip_to=1000.0)
>>> host = Bench(); _ = b.reset(host); b.fill(host, 200.0)
>>> b.position = 995.0
>>> while b.pouring_possible():
...     _ = b.advance(host, 0.001); host.now_ns += 1_000_000
>>> round(host.now_ns / 1e9, 3), b.load_g, b.bin_g, host.events[-1].kind, host.events[-1].data["fraction"]
(2.5, 0.0, 200.0, 'pour ended', 1.0)
"""

from __future__ import annotations

from typing import Any

from plants.components.component import Host
from plcsim.plant import Drawable, SignalSpec


class Bucket:
    """The bucket, its load and the bin it pours into (see the module docstring).

    Args:
        name: the bucket (subject of ``bucket filled``).
        bin_name: the bin it pours into (subject of ``pour ended`` and ``mixer discharged``).
        tip_from: the track position (mm) where the tilt starts.
        tip_to: the track position where it reaches ``tilt_max``.
        tilt_max: the tilt at ``tip_to`` and beyond (degrees).
        pour_from: the tilt where the load starts to flow.
        pour_full: the tilt from which it flows at the full rate.
        rate_g_s: the full flow rate (g/s).
        capacity_g: what one fill puts into the bucket.
    """

    EVENTS = frozenset({"bucket filled", "pour ended", "mixer discharged"})

    def __init__(
        self,
        name: str,
        bin_name: str,
        *,
        tip_from: float,
        tip_to: float,
        tilt_max: float = 120.0,
        pour_from: float = 90.0,
        pour_full: float = 105.0,
        rate_g_s: float = 80.0,
        capacity_g: float = 200.0,
    ) -> None:
        if not (tip_from < tip_to and 0 < pour_from < pour_full <= tilt_max):
            raise ValueError(f"bucket {name}: need tip_from < tip_to and 0 < pour_from < pour_full <= tilt_max")
        self.name, self.bin_name = name, bin_name
        self.tip_from, self.tip_to, self.tilt_max = float(tip_from), float(tip_to), float(tilt_max)
        self.pour_from, self.pour_full = float(pour_from), float(pour_full)
        self.rate, self.capacity = float(rate_g_s), float(capacity_g)
        self.s_pour = self.position_at(self.pour_from)

    def position_at(self, tilt: float) -> float:
        """The track position at which the bucket reaches ``tilt``."""
        return self.tip_from + (self.tip_to - self.tip_from) * tilt / self.tilt_max

    # --- the component protocol ------------------------------------------------------------------------------
    def specs(self) -> list[SignalSpec]:
        return []

    def subjects(self) -> set[str]:
        return {self.name, self.bin_name}

    def reset(self, host: Host) -> bool:
        self.position = 0.0
        self.load_g = 0.0
        self.bin_g = 0.0
        self.flow_g_s = 0.0
        self.pour: float | None = None  # the load when the pour under way began
        return False

    def actuate(self, host: Host, signal: str, value: Any) -> bool:
        raise KeyError(f"{self.name} has no actuator {signal!r}")

    @property
    def tilt(self) -> float:
        """The bucket's tilt now (degrees)."""
        return self.tilt_at(self.position)

    def tilt_at(self, position: float) -> float:
        """The bucket's tilt (degrees) with the carriage at ``position`` on the track."""
        u = (position - self.tip_from) / (self.tip_to - self.tip_from)
        return self.tilt_max * min(1.0, max(0.0, u))

    def pouring_possible(self) -> bool:
        """Whether a step can change the load (tilted far enough with something in it, or a pour to close)."""
        return self.pour is not None or (self.load_g > 0.0 and self.position > self.s_pour)

    def fill(self, host: Host, grams: float | None = None) -> None:
        """The dosing hopper fills the bucket (to ``capacity_g`` unless ``grams`` says otherwise)."""
        self.load_g = float(self.capacity if grams is None else grams)
        host.emit("bucket filled", self.name, mass_g=self.load_g)

    def discharge(self, host: Host) -> None:
        """The bin (the mixer) empties its batch."""
        host.emit("mixer discharged", self.bin_name, mass_g=round(self.bin_g, 3))
        self.bin_g = 0.0

    def advance(self, host: Host, dt: float) -> bool:
        tilt = self.tilt
        share = min(1.0, (tilt - self.pour_from) / (self.pour_full - self.pour_from)) if tilt > self.pour_from else 0.0
        dm = min(self.load_g, self.rate * share * dt)
        if dm > 0.0:
            if self.pour is None:
                self.pour = self.load_g
            self.load_g -= dm
            if self.load_g < 1e-9:
                self.load_g = 0.0
            self.bin_g += dm
        self.flow_g_s = dm / dt if dt > 0 else 0.0
        if self.pour is not None and (self.load_g == 0.0 or share == 0.0):
            batch = self.pour
            poured = batch - self.load_g
            host.emit(
                "pour ended",
                self.bin_name,
                batch_g=round(batch, 3),
                poured_g=round(poured, 3),
                fraction=round(poured / batch, 4),
                left_g=round(self.load_g, 3),
            )
            self.pour = None
            self.flow_g_s = 0.0
        return self.pouring_possible()

    def static_drawables(self) -> list[Drawable]:
        return []

    def dynamic_drawables(self) -> list[Drawable]:
        return []
