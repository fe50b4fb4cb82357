"""SORT (4.3.17): a belt with five light barriers, an analog colour sensor, three pistons, a compressor and bins,
seen from above.

Parameters are the proposals of ``spec/exercises.md`` §5.8 (mm, y up, the belt along +x over y = -30…30):

* belt D1_VPRED: 500 × 60 mm, 50 mm/s forward, τ 50 ms; parts ride on it by friction (μ 0.6) and slide to a stop
  on the table (μ 0.3) once they are off it;
* parts: the §5.1 sorting-line piece, Ø25 mm × 25 mm, 10 g, modelled as a 25 × 25 mm block seen from above
  (its corners do not matter here); property ``colour=1|2|3`` (or ``colour_raw=`` for any raw mean);
* barriers (True = interrupted; the NC wiring is the exercise's): OS1_Vstup 30, OS2_Detekcia 120, OS3_Farba1 210,
  OS4_Farba2 310, OS5_Farba3 410 mm;
* FARBA: spot Ø5 mm at x = 110 mm on the belt's centre line; colour means 1 white 5000, 2 red 13000, 3 blue 21000,
  bare belt 26500 raw, σ 500; ambient light offset by the rig verb ``set_ambient``; a new reading every 5 ms (the
  analog input's conversion cycle, held in between: :mod:`plants.components.colour_sensor`);
* pistons Piest1_Farba1…Piest3_Farba3 at x = 245 / 345 / 445 mm on the +y side, pushing toward -y across the belt:
  plate 50 mm along the belt, stroke 70 mm, 200 mm/s out (0.35 s), spring back at 280 mm/s (0.25 s), valve 20 ms,
  5 N at full pressure; they move only above 30 % of full pressure; at rest retracted a piston is parked out of
  the solver (a static plate stands in for it);
* Kompresor: pressure τ 0.1 s up, 0.5 s down (the pistons' ``supply``), in closed form of the time since the last
  change; rig verb ``fail_compressor``;
* bins bin1…bin3 beyond the belt's -y edge in front of each piston (x ± 40 mm), ``unsorted`` after the belt end:
  ``part in bin`` (data ``colour``) when a part reaches one; 0.6 s later it lies still there and leaves the physics
  (it is still drawn).

Stations: ``OS1`` (a part centred on the entry barrier, ``offset_mm`` along the belt).

>>> s = Sort()
>>> _ = s.place("OS1", colour=2); s.actuate("D1_VPRED", True)
>>> while not s.sensors["OS2_Detekcia"]:
...     s.step(1_000_000)
>>> round(s.now_ns / 1e9, 2), 11000 < s.sensors["FARBA"] < 15000
(1.58, True)
"""

from __future__ import annotations

from typing import Any

from plants.components.bins import Bins
from plants.components.colour_sensor import ColourSensor
from plants.components.compressor import Compressor
from plants.components.piston import Piston
from plants.components.top_belt import TopBelt
from plants.components.top_view import Beam, TopViewPlant
from plants.components.workpiece import WorkpieceSpec
from plcsim.plant import RigVerb, Station

PIECE = WorkpieceSpec(length=25.0, depth=25.0, height=25.0, mass_g=10.0)
BELT_LENGTH, HALF_WIDTH = 500.0, 30.0
BARRIERS = {"OS1_Vstup": 30.0, "OS2_Detekcia": 120.0, "OS3_Farba1": 210.0, "OS4_Farba2": 310.0, "OS5_Farba3": 410.0}
PISTONS = {"Piest1_Farba1": 245.0, "Piest2_Farba2": 345.0, "Piest3_Farba3": 445.0}
COLOURS = {1: 5000.0, 2: 13000.0, 3: 21000.0}
SETTLE_NS = 600_000_000  # a part that reached a bin has come to rest there after this long: it leaves the physics
# how a part is drawn: red and blue as they are, white as yellow (a white outline vanishes on the light table)
RGB = {1: (235, 190, 0), 2: (215, 45, 40), 3: (40, 80, 215)}
# where the names are written (mm): in rows above the belt and below it, clear of one another at the recording's
# scale (tests/rigs/test_label_layout.py) and of the band under the belt where the parts' names pass
ROW_TOP, ROW_HIGH, ROW_LOW, ROW_UNDER = 128.0, 92.0, 62.0, -36.0
BARRIER_LABEL_Y = {"OS1_Vstup": ROW_LOW, "OS2_Detekcia": ROW_HIGH, "OS3_Farba1": ROW_LOW, "OS4_Farba2": ROW_HIGH}
BIN_LABEL_Y = -93.0

SET_AMBIENT = RigVerb(
    "set_ambient",
    "set_ambient",
    "sensor",
    "set the ambient light on {target} to {offset:+g} raw",
    targets="colour_sensors",
)
FAIL_COMPRESSOR = RigVerb(
    "fail_compressor", "fail_compressor", "compressor", "fail compressor {target}", targets="compressors", fault=True
)


class Sort(TopViewPlant):
    """SORT: sensors OS1_Vstup … OS5_Farba3 (True = interrupted) and FARBA (raw); actuators D1_VPRED, Piest1_Farba1
    … Piest3_Farba3, Kompresor."""

    VERBS = {"set_ambient": SET_AMBIENT, "fail_compressor": FAIL_COMPRESSOR}
    PART_PROPERTIES = {
        **TopViewPlant.PART_PROPERTIES,
        "colour": "1 white, 2 red, 3 blue: what the colour sensor reads (drawn yellow, red, blue)",
        "colour_raw": "the colour sensor's mean reading of the part, raw 0..27648 (instead of a colour)",
    }

    def __init__(self, *, seed: int = 0) -> None:
        self.belt = TopBelt(
            "D1", "D1_VPRED", (0.0, -HALF_WIDTH, BELT_LENGTH, HALF_WIDTH), speed=50.0, label_at=(185.0, ROW_UNDER)
        )
        self.air = Compressor("Kompresor", "Kompresor", at=(40.0, 80.0), label_at=(40.0, ROW_TOP))
        self.colour = ColourSensor(
            "FARBA",
            110.0,
            0.0,
            colours=COLOURS,
            doc="colour sensor at 110 mm, raw 0..27648",
            label_at=(100.0, ROW_UNDER),
        )
        self.colour_sensors = {"FARBA": self.colour}
        self.compressors = {"Kompresor": self.air}
        beams = [
            Beam(n, x, -HALF_WIDTH, HALF_WIDTH, label_y=BARRIER_LABEL_Y.get(n, ROW_LOW)) for n, x in BARRIERS.items()
        ]
        pistons = [
            Piston(
                f"P{k}",
                valve,
                origin=(x, HALF_WIDTH + 2.0),
                direction=(0.0, -1.0),
                stroke=70.0,
                plate=(50.0, 6.0),
                extend_speed=200.0,
                retract_speed=280.0,
                valve_s=0.02,
                threshold=0.3,
                supply=self.air.fraction,
                park=True,
                doc=f"piston {k} forward (single-acting, spring return; needs the compressor's pressure)",
                label_back=ROW_TOP - HALF_WIDTH - 2.0 - 6.0,
            )
            for k, (valve, x) in enumerate(PISTONS.items(), start=1)
        ]
        bins = {f"bin{k}": (x - 40.0, -110.0, x + 40.0, -HALF_WIDTH - 8.0) for k, x in enumerate(PISTONS.values(), 1)}
        bins["unsorted"] = (BELT_LENGTH + 2.0, -HALF_WIDTH, BELT_LENGTH + 60.0, HALF_WIDTH)
        labels = {k: (0.5 * (box[0] + box[2]), BIN_LABEL_Y) for k, box in bins.items()}
        labels["unsorted"] = (BELT_LENGTH + 31.0, ROW_LOW)
        self.bins = Bins(bins, label_at=labels)
        super().__init__(
            "SORT",
            components=[self.belt, self.air, self.colour, *beams, *pistons, self.bins],
            stations=[Station("OS1", BARRIERS["OS1_Vstup"], 0.0, "centred on the entry barrier OS1_Vstup")],
            table=(-20.0, -120.0, BELT_LENGTH + 70.0, 120.0),
            workpiece=PIECE,
            seed=seed,
        )

    def reset(self, *, seed: int | None = None) -> None:
        super().reset(seed=seed)
        self._settling: list[tuple[int, str]] = []  # (when, part): parts in a bin, taken out of the physics then

    def emit(self, kind: str, subject: str, part: str | None = None, **data: Any) -> None:
        super().emit(kind, subject, part, **data)
        if kind == "part in bin" and part is not None:
            self._settling.append((self.now_ns + SETTLE_NS, part))

    def step(self, dt_ns: int) -> None:
        """One step; parts that have lain in a bin for 0.6 s stop being simulated (they cost the solver)."""
        super().step(dt_ns)
        while self._settling and self._settling[0][0] <= self.now_ns:
            _, pid = self._settling.pop(0)
            if pid in self.parts:
                self.retire(pid)

    def place(self, station: str, **kw: Any) -> str:
        """Put a part at ``station`` (``colour=1|2|3``: drawn yellow (white), red or blue)."""
        colour = kw.get("colour")
        if colour in RGB:
            kw.setdefault("color", RGB[colour])
        return super().place(station, **kw)

    def set_ambient(self, name: str, offset: float = 0.0) -> None:
        """Condition (rig verb ``set_ambient``): ambient light adds ``offset`` raw units to the colour readings."""
        self.colour_sensors[name].set_ambient(self, offset)
        self._still = False

    def fail_compressor(self, name: str) -> None:
        """Fault (rig verb ``fail_compressor``): the compressor runs but builds no pressure."""
        if self.compressors[name].fail(self, True):
            self.assembly.wake(self.compressors[name])
        self._still = False
