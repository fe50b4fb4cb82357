"""Conveyor rigs of the course: CONV1 (one belt), CONV3 (three in series), CONV2x2 (two belts, two beams each).

Side view, y up, mm. Parameters are the proposals of ``spec/exercises.md`` §5.1–5.4:

* belts 50 mm wide, top surface 40 mm above the base, 50 mm/s forward only, first-order drive with τ = 50 ms,
  belt/part μ = 0.6; belts in series are 5 mm apart, the gap bridged by a dead plate 0.5 mm below the belt surface;
* light barriers 10 mm above the belt surface, beam spot 2 mm wide (along the travel); ``True`` = interrupted
  (physical state; NO/NC is the wiring's job);
* workpiece 30 × 30 × 20 mm, 12 g (``plants.components.workpiece``);
* the last belt's downstream end is open by default (a part carried past it falls off: ``part fell off``);
  ``end="stop"`` puts a fixed end stop there instead (parts pile up against it: ``end stop hit``).

Stations (where ``place``/``remove`` act): every light barrier (a part placed there is centred on the nominal beam
position, ``offset_mm`` moves it downstream), and each belt (the belt's upstream end: ``offset_mm`` is the position of
the part's centre along the belt; ``remove``/``hold`` on a belt station pick its front-most part). CONV1 calls its
belt station ``belt``; the multi-belt rigs use the belt names ``D1``, ``D2``, ``D3``.

Nominal times (§5), and what the plant gives (``tests/rigs/test_conveyors.py`` measures them at dt = 1 ms). The part is
placed centred on the first barrier at t = 0; a beam sees a new part one step later (t = 1 ms). Times are between
**rising edges** of the two barriers (for CONV1: S2↑ − S1↑, D1 switched on at S1↑ as the reference program does; for
the other rigs all belts run from t = 0). A beam is cut when the part's leading face reaches ``beam x − 1 mm`` (the
beam spot is 2 mm wide); a start from rest adds the drive's lag τ = 50 ms (the part's own acceleration, μ·g ≈ 5.9 m/s²,
is far above the belt's 1 m/s² and adds nothing measurable):

========================  ===========  =========================================  ========
rig: from ↑ → to ↑        §5 proposal  geometry                                   measured
========================  ===========  =========================================  ========
CONV1 S1 → S2             4.8 s        (295 − 1 − 55) / 50 + 0.05 = 4.83 s        4.830 s
CONV3 D1_OS → D2_OS       4.9 s        (300 − 1 − 55) / 50 + 0.05 = 4.93 s        4.930 s
CONV3 D2_OS → D3_OS       8.4 s        (720 − 300) / 50 = 8.40 s (running)        8.400 s
CONV2x2 D1_OS1 → D1_OS2   4.2 s        (265 − 1 − 55) / 50 + 0.05 = 4.23 s        4.230 s
CONV2x2 D1_OS2 → D2_OS1   1.6 s        (345 − 265) / 50 = 1.60 s                  1.600 s
CONV2x2 D2_OS1 → D2_OS2   4.5 s        (570 − 345) / 50 = 4.50 s                  4.500 s
========================  ===========  =========================================  ========

The proposals are geometrically consistent; no parameter was changed. Crossing a 5 mm gap costs the part < 1 ms.
A part stopped by switching D1 off at S2↑ coasts v·τ ≈ 2.5 mm (measured 2.53 mm) and rests spanning ≈ 267–297 mm
with S2 still interrupted, 33 mm from the belt end (§5.2 says 268–298: it assumed the beam cut at its centre line).
On CONV3 the part stopped at D3_OS↑ rests spanning ≈ 182–212 mm of D3 (§5.3: 183–213).

Performance (stepped alone at dt = 1 ms, belt running, best of 7 runs on the project's 2-core machine): CONV1 with
no part 0.16 µs per step (the physics is skipped), one part 1.4 µs, five parts riding apart 4.7 µs, five parts
piled against the end stop 8.8 µs; in the 0.66 s after a motor command (the belt speed is written each step while the
drive settles) one part costs 3.5 µs.

>>> c = Conv1()
>>> pid = c.place("S1")
>>> c.actuate("D1", True)
>>> while not c.sensors["S2"]:
...     c.step(1_000_000)
>>> round(c.now_ns / 1e9, 2)
4.83
"""

from __future__ import annotations

import itertools
from collections.abc import Iterable, Sequence
from dataclasses import dataclass

from plants.components.belt import Belt
from plants.components.component import Component
from plants.components.frame import DeadPlate, EndStop
from plants.components.light_barrier import LightBarrier
from plants.components.panel import OperatorPanel
from plants.components.side_view import SideViewPlant
from plcsim.plant import Station

TOP = 40.0  # belt surface above the base, mm
SPEED = 50.0  # mm/s
GAP = 5.0  # transfer gap between belts in series, mm
BEAM_HEIGHT = 10.0  # beam above the belt surface, mm
BEAM_WIDTH = 2.0  # beam spot along the travel, mm


@dataclass(frozen=True)
class BeltLayout:
    """A belt of a line: its name, the actuator that drives it forward, its length (mm)."""

    name: str
    actuator: str
    length: float


@dataclass(frozen=True)
class BarrierLayout:
    """A light barrier: its signal name, the belt it sits on, its distance from that belt's upstream end (mm)."""

    name: str
    belt: str
    at: float


class ConveyorLine(SideViewPlant):
    """Belts in series along +x, light barriers over them, an open end or an end stop after the last one.

    Args:
        name: plant name.
        belts, barriers: the layout (see :class:`BeltLayout`, :class:`BarrierLayout`).
        belt_station: name of the belt station for a one-belt line (``belt``); multi-belt lines use the belt names.
        end: ``open`` (parts fall off the last belt's end) or ``stop`` (a fixed end stop).
        speed, tau_s, friction: belt drive (mm/s, s) and belt/part μ.
        gap: transfer gap between belts (mm), bridged by a dead plate.
        top: belt surface height above the base (mm).
        beam_height, beam_width: light-barrier beam above the belt surface and its spot width (mm).
        lamps, buttons, switches: an optional operator panel beside the line (e.g. ``lamps=("LED",)`` for 4.3.8).
        components: further pieces on the component protocol (a press ram's axis), see ``SideViewPlant``.
        seed: initial seed (the rig has no randomness of its own).
    """

    def __init__(
        self,
        name: str,
        belts: Sequence[BeltLayout],
        barriers: Sequence[BarrierLayout],
        *,
        belt_station: str | None = None,
        end: str = "open",
        speed: float = SPEED,
        tau_s: float = 0.05,
        friction: float = 0.6,
        gap: float = GAP,
        top: float = TOP,
        beam_height: float = BEAM_HEIGHT,
        beam_width: float = BEAM_WIDTH,
        lamps: Iterable[str] = (),
        buttons: Iterable[str] = (),
        switches: Iterable[str] = (),
        components: Iterable[Component] = (),
        seed: int = 0,
    ) -> None:
        if end not in ("open", "stop"):
            raise ValueError(f"{name}: end must be 'open' or 'stop', not {end!r}")
        self.end = end
        self.layout = (tuple(belts), tuple(barriers))
        comps: list[Belt] = []
        x = 0.0
        for bl in belts:
            doc = f"belt {bl.name} ({bl.length:g} mm) forward at {speed:g} mm/s while True (τ {tau_s * 1e3:g} ms)"
            b = Belt(
                bl.name,
                x,
                bl.length,
                top,
                speed=speed,
                tau_s=tau_s,
                friction=friction,
                forward=bl.actuator,
                docs={bl.actuator: doc},
            )
            comps.append(b)
            x += bl.length + gap
        by_name = {b.name: b for b in comps}
        plates = [DeadPlate(f"plate_{a.name}_{b.name}", a.x1, b.x0, top) for a, b in itertools.pairwise(comps)]
        lbs = []
        stations = []
        for bar in barriers:
            if bar.belt not in by_name:
                raise ValueError(f"{name}: barrier {bar.name} is on unknown belt {bar.belt!r}")
            b = by_name[bar.belt]
            doc = (
                f"light barrier {bar.at:g} mm from the upstream end of {b.name}, {beam_height:g} mm above the belt: "
                "True while interrupted"
            )
            lbs.append(LightBarrier(bar.name, b.x0 + bar.at, top + beam_height, width=beam_width, doc=doc))
            stations.append(Station(bar.name, b.x0 + bar.at, top, f"centred on the {bar.name} beam"))
        belt_stations: dict[str, Belt] = {}
        if belt_station is not None:
            if len(comps) != 1:
                raise ValueError(f"{name}: belt_station is for a one-belt line")
            belt_stations[belt_station] = comps[0]
        else:
            for b in comps:
                belt_stations[b.name] = b
        for sname, b in belt_stations.items():
            stations.append(Station(sname, b.x0, top, f"upstream end of belt {b.name}; offset_mm = position along it"))
        stops = [EndStop("end_stop", comps[-1].x1, top)] if end == "stop" else []
        panel = []
        lamps, buttons, switches = tuple(lamps), tuple(buttons), tuple(switches)
        if lamps or buttons or switches:
            panel.append(
                OperatorPanel(
                    buttons, switches, lamps, origin=(comps[-1].x1 + 30.0, 0.0), lamp_colors={"LED": (255, 60, 40)}
                )
            )
        super().__init__(
            name,
            components=[*lbs, *comps, *plates, *stops, *panel, *components],
            stations=stations,
            belt_stations=belt_stations,
            seed=seed,
        )


class Conv1(ConveyorLine):
    """CONV1 (4.3.5–4.3.8, 4.3.14, 4.3.15): one belt 330 × 50 mm, S1 at 40 mm, S2 at 295 mm, motor D1.

    Signals: sensors ``S1``, ``S2`` (True = beam interrupted); actuator ``D1`` (belt forward). Stations ``S1``,
    ``S2``, ``belt``. Options: ``end="open"|"stop"``, ``lamps=("LED",)`` for the alarm lamp of 4.3.8.
    """

    def __init__(self, *, length: float = 330.0, s1: float = 40.0, s2: float = 295.0, **kw) -> None:
        super().__init__(
            kw.pop("name", "CONV1"),
            [BeltLayout("D1", "D1", length)],
            [BarrierLayout("S1", "D1", s1), BarrierLayout("S2", "D1", s2)],
            belt_station="belt",
            **kw,
        )


class Conv3(ConveyorLine):
    """CONV3 (4.3.9): belts D1, D2, D3 of 250 mm in series; D1_OS at 40 mm of D1, D2_OS at 45 mm of D2, D3_OS at
    210 mm of D3; motors D1_VPRED, D2_VPRED, D3_VPRED. Stations ``D1_OS``, ``D2_OS``, ``D3_OS``, ``D1``, ``D2``, ``D3``.
    """

    def __init__(self, *, length: float = 250.0, **kw) -> None:
        super().__init__(
            kw.pop("name", "CONV3"),
            [
                BeltLayout("D1", "D1_VPRED", length),
                BeltLayout("D2", "D2_VPRED", length),
                BeltLayout("D3", "D3_VPRED", length),
            ],
            [
                BarrierLayout("D1_OS", "D1", 40.0),
                BarrierLayout("D2_OS", "D2", 45.0),
                BarrierLayout("D3_OS", "D3", 210.0),
            ],
            **kw,
        )


class Conv2x2(ConveyorLine):
    """CONV2x2 (4.3.10): belts D1, D2 of 300 mm; D1_OS1/D1_OS2 and D2_OS1/D2_OS2 at 40/265 mm of each belt;
    motors D1_VPRED, D2_VPRED. Stations: the four barriers, ``D1``, ``D2``. The textbook wires all four barriers NC:
    that is the wiring's business, the plant reports True = interrupted.
    """

    def __init__(self, *, length: float = 300.0, **kw) -> None:
        super().__init__(
            kw.pop("name", "CONV2x2"),
            [BeltLayout("D1", "D1_VPRED", length), BeltLayout("D2", "D2_VPRED", length)],
            [
                BarrierLayout("D1_OS1", "D1", 40.0),
                BarrierLayout("D1_OS2", "D1", 265.0),
                BarrierLayout("D2_OS1", "D2", 40.0),
                BarrierLayout("D2_OS2", "D2", 265.0),
            ],
            **kw,
        )
