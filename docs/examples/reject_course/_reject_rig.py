"""REJECT: a short belt with a light barrier at each end and a piston halfway that pushes bad parts into a bin.

Seen from above (mm, y up; the belt runs along +x over y = -25…25):

* belt D1: 300 × 50 mm, 50 mm/s forward while D1 is True;
* light barriers S1 at x = 20 mm (the entry, where parts are placed) and S2 at x = 280 mm (the end), True while a part
  interrupts them;
* inspection sensor B1, a spot at x = 150 mm on the belt's centre line: True while a *bad* part (``bad=True``) covers
  it; good parts pass it unseen;
* piston Y1 at x = 150 mm on the +y side, pushing toward -y across the belt (stroke 80 mm, 200 mm/s out, spring back);
* bins ``reject`` beyond the belt's -y edge in front of the piston and ``good`` after the belt's end: ``part in bin``
  (data ``bad``) when a part reaches one.

>>> rig = Reject()
>>> rig.actuate("D1", True)
>>> _ = rig.place("S1", bad=True)
>>> while not rig.sensors["B1"]:  # the belt carries it to the inspection spot
...     rig.step(1_000_000)
>>> round(rig.now_ns / 1e9, 1)
2.3
"""

from __future__ import annotations

from typing import Any

from plants.components import Beam, Bins, Piston, SpotSensor, TopBelt, TopViewPlant, WorkpieceSpec
from plcsim.plant import Station

LENGTH, HALF_WIDTH = 300.0, 25.0
PART = WorkpieceSpec(length=25.0, depth=25.0, height=25.0, mass_g=10.0)
RED, GREEN = (215, 45, 40), (60, 160, 70)  # how bad and good parts are drawn


class Reject(TopViewPlant):
    """REJECT: sensors S1, S2, B1 (True = a part there; B1: a bad part); actuators D1 (belt), Y1 (piston)."""

    PART_PROPERTIES = {
        **TopViewPlant.PART_PROPERTIES,
        "bad": "True for a part to reject: B1 sees it, the bins report it, it is drawn red",
    }

    def __init__(self, *, seed: int = 0) -> None:
        super().__init__(
            "REJECT",
            components=[
                TopBelt("belt", "D1", (0.0, -HALF_WIDTH, LENGTH, HALF_WIDTH), speed=50.0),
                Beam("S1", 20.0, -HALF_WIDTH, HALF_WIDTH, doc="light barrier at the entry (x = 20 mm)"),
                Beam("S2", 280.0, -HALF_WIDTH, HALF_WIDTH, doc="light barrier at the end (x = 280 mm)"),
                SpotSensor(
                    "B1", 150.0, 0.0, doc="inspection at x = 150 mm: True while a bad part covers it", sees="bad"
                ),
                Piston(
                    "piston",
                    "Y1",
                    origin=(150.0, HALF_WIDTH + 2.0),
                    direction=(0.0, -1.0),
                    stroke=80.0,
                    plate=(50.0, 6.0),
                    extend_speed=200.0,
                    retract_speed=280.0,
                    doc="piston forward (single-acting, spring return)",
                ),
                Bins(
                    {"reject": (110.0, -110.0, 190.0, -HALF_WIDTH - 8.0), "good": (LENGTH + 2.0, -40.0, 360.0, 40.0)},
                    report=("bad",),
                ),
            ],
            stations=[Station("S1", 20.0, 0.0, "centred on the entry barrier S1")],
            table=(-20.0, -120.0, 370.0, 100.0),
            workpiece=PART,
            seed=seed,
        )

    def place(self, station: str, **kw: Any) -> str:
        """Put a part at ``station``; ``bad=True`` makes it one B1 sees (drawn red; good parts green)."""
        kw.setdefault("bad", False)
        kw.setdefault("color", RED if kw["bad"] else GREEN)
        return super().place(station, **kw)
