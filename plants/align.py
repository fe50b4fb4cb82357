"""ALIGN (4.3.12): a piston pushes a crooked part flat against a fence, seen from above.

Parameters are the proposals of ``spec/exercises.md`` §5.5, in top-view coordinates (mm, y up, the fence along
y = 0, the piston above it pushing toward -y):

* part: block 60 × 40 mm (60 along the fence), 30 g, floor μ = 0.3; placed at the station ``table`` with
  ``offset_mm`` = the gap between the fence and its nearest corner (§5.5: 0–15 mm) and ``angle_deg`` (±15°);
* OS: a reflex sensor, spot Ø6 mm at (0, 20): covered by any part on the table (NO wiring is the exercise's);
* piston: monostable valve PIEST_CHOD_VPRED (20 ms, as §5.8's), plate 50 mm wide, out at 80 mm/s with at most 5 N
  (40 mm in 0.5 s), spring back at 67 mm/s with at most 2 N (0.6 s). Retracted, the plate's face is at y = 80;
  **full stroke** (s = 40 mm) is the face at y = 40, the part pressed flat on the fence; the groove (the mechanical
  end stop) ends 2 mm further (s = 42), where the plate stops with no part;
* PIEST_SNIMAC_VZAD: reed switch, actuated for s ≤ 2 mm; PIEST_SNIMAC_VPRED: actuated for s ≥ 38 mm ("within 2 mm
  of full stroke"). A part still turned by more than ≈ 2° holds the plate short of 38 mm (40·cos θ + 60·sin θ > 42),
  so the front switch means "the part is flat".

**Alignment** is measured when the plate is back (``piston retracted`` after a full stroke) and when a part is
removed: ``alignment measured`` (subject ``table``) with data ``gap_mm`` (the larger distance of the two corners of
the part's fence-side edge from the fence), ``angle_deg`` (its turn from square, 0…45°) and ``aligned`` (≤ 1 mm and
≤ 2°, the task's tolerance). ``part removed`` carries the same data.

Rig verb: ``jam_piston(piston, t=...)`` — the rod sticks where it is (the task defines no timeout: informational).

>>> a = Align()
>>> pid = a.place("table", offset_mm=10.0, angle_deg=12.0); a.step(1_000_000); a.sensors["OS"]
True
>>> a.actuate("PIEST_CHOD_VPRED", True)
>>> while not a.sensors["PIEST_SNIMAC_VPRED"]:
...     a.step(1_000_000)
>>> a.actuate("PIEST_CHOD_VPRED", False)
>>> while not a.sensors["PIEST_SNIMAC_VZAD"]:
...     a.step(1_000_000)
>>> for _ in range(100): a.step(1_000_000)
>>> m = [e.data for e in a.events if e.kind == "alignment measured"][0]
>>> m["aligned"], m["gap_mm"] <= 1.0, m["angle_deg"] <= 2.0
(True, True, True)
"""

from __future__ import annotations

import math
from typing import Any

from plants.components.limit_switch import LimitSwitch
from plants.components.piston import Piston
from plants.components.top_view import Fence, SpotSensor, TopPart, TopViewPlant
from plants.components.workpiece import WorkpieceSpec
from plcsim.plant import RigVerb, Station

BLOCK = WorkpieceSpec(length=60.0, depth=40.0, height=20.0, mass_g=30.0)
STROKE = 40.0  # full stroke: the part flat on the fence
OVERTRAVEL = 2.0  # groove beyond the full stroke (the plate's end stop with no part)
TOLERANCE_MM = 1.0
TOLERANCE_DEG = 2.0

JAM_PISTON = RigVerb(
    "jam_piston",
    "jam_piston",
    "piston",
    "jam piston {target}",
    targets="pistons",
    doc="the piston rod sticks where it is (commanded or not)",
    fault=True,
)


class Align(TopViewPlant):
    """ALIGN: sensors OS, PIEST_SNIMAC_VPRED, PIEST_SNIMAC_VZAD (True = actuated); actuator PIEST_CHOD_VPRED."""

    VERBS = {"jam_piston": JAM_PISTON}
    EXTRA_EVENTS = frozenset({"alignment measured"})

    def __init__(self, *, seed: int = 0) -> None:
        self.piston = Piston(
            "PIEST",
            "PIEST_CHOD_VPRED",
            origin=(0.0, BLOCK.depth + STROKE),
            direction=(0.0, -1.0),
            stroke=STROKE + OVERTRAVEL,
            full=STROKE,
            plate=(50.0, 6.0),
            extend_speed=80.0,
            retract_speed=67.0,
            force_n=5.0,
            spring_n=2.0,
            valve_s=0.02,
            rear=LimitSwitch("PIEST_SNIMAC_VZAD", -1.0, 2.0, doc="rear reed switch: True within 2 mm of retracted"),
            front=LimitSwitch(
                "PIEST_SNIMAC_VPRED",
                STROKE - 2.0,
                STROKE + OVERTRAVEL + 1.0,
                doc="front reed switch: True within 2 mm of the full stroke (the part flat on the fence)",
            ),
            doc="piston forward (monostable valve; False = spring return)",
        )
        self.pistons = {"PIEST": self.piston}
        components = [
            Fence("fence", (-70.0, 0.0), (70.0, 0.0)),
            SpotSensor("OS", 0.0, 20.0, 3.0, doc="reflex sensor on the table: True while a part covers its spot"),
            self.piston,
        ]
        station = Station("table", 0.0, 0.0, "in front of the piston; offset_mm = gap to the fence")
        super().__init__(
            "ALIGN",
            components=components,
            stations=[station],
            table=(-90.0, -10.0, 90.0, 150.0),
            workpiece=BLOCK,
            seed=seed,
        )
        self.EVENTS = self.EVENTS | self.EXTRA_EVENTS

    def pose_at(self, station: Station, offset_mm: float, angle_deg: float) -> tuple[float, float, float]:
        """The part's centre so that its nearest corner is ``offset_mm`` from the fence, turned by ``angle_deg``."""
        a = math.radians(angle_deg)
        half_y = 0.5 * (BLOCK.depth * abs(math.cos(a)) + BLOCK.length * abs(math.sin(a)))
        return (station.x, offset_mm + half_y + 1e-3, a)

    def emit(self, kind: str, subject: str, part: str | None = None, **data: Any) -> None:
        super().emit(kind, subject, part, **data)
        if kind == "piston retracted":
            for p in self.parts.values():
                self.emit("alignment measured", "table", p.id, **self.measure_part(p))

    def measure_part(self, p: TopPart) -> dict[str, Any]:
        corners = p.corners()
        low = sorted(corners[:, 1])[:2]  # the fence-side edge
        gap = float(max(low))
        turn = math.degrees(p.body.angle) % 90.0
        angle = min(turn, 90.0 - turn)
        return {
            "gap_mm": round(gap, 3),
            "angle_deg": round(angle, 3),
            "aligned": gap <= TOLERANCE_MM and angle <= TOLERANCE_DEG,
        }

    def jam_piston(self, name: str) -> None:
        """Fault (rig verb ``jam_piston``): the rod of ``name`` sticks where it is."""
        self.assembly.jam(self, name, True)
        self._still = False
