"""HBW (4.3.18): a stacker crane serving a 3 × 3 high-bay rack, axes X, Y and Z with discrete position cams.

Kinematic, y up, mm. The parameters are the proposals of ``spec/exercises.md`` §5.9; changes are listed below.

* **X** (travel along the rack, ``x_vpravo`` right = +, ``x_vlavo`` left): cams ``x1``, ``x2``, ``x3`` at 100, 220,
  340 mm (the columns' centres), zone ±6 mm; end stops at 40 and 400 mm; 100 mm/s; τ = 20 ms.
* **Y** (the fork's height, the top of its tines; ``y_hore`` up = +, ``y_dole`` down): cams ``y1``…``y6`` at 50, 70,
  150, 170, 250, 270 mm, zone ±4 mm; odd = 10 mm below a shelf's top, even = 10 mm above it (text issue 11); shelf
  tops at 60 / 160 / 260 mm; end stops at 30 and 290 mm; 60 mm/s; τ = 20 ms.
* **Z** (the fork's depth, + into the rack; ``z_vpred`` forward, ``z_vzad`` back): cams ``z1`` = −70 mm (back,
  loading), ``z2`` = 0 (middle, transport), ``z3`` = +80 mm (forward, in the rack), zone ±4 mm; end stops at −80 and
  +90 mm; 80 mm/s; τ = 20 ms.
* **Rack** (:class:`~plants.components.rack.Rack`): places ``R11`` … ``R33`` (``R<column><row>``, [1,1] bottom
  left as the textbook counts), each 80 mm deep from Z = 40 mm, slotted shelves; parts 40 × 40 × 30 mm.

Changes to §5.9: the speeds are about twice §5.9's (60 / 30 / 40 mm/s) and τ is 20 ms, not 30 ms, so that a put-in
takes ≈ 5 s instead of ≈ 12 s and the exercise's scenarios stay short enough to grade every solution in budget.

**Stopping distance against cam zones** (spec next-phase §a.4). A drive switched off coasts ``speed × τ``: 2.0 mm on
X, 1.2 mm on Y, 1.6 mm on Z, plus what it travels until the program's next scan switches it off — inside the
±6 / ±4 mm zones at a 1 ms scan (the cams are 12 and 8 mm long; the margin is 4, 2.8 and 2.4 mm: a scan of up to
≈ 30 ms on Z). Nothing else stops a carriage: a program that
switches its drive off late, or a cam that fails, lets the carriage run on through the zone and out of it, so the
edge-counting estimate of the textbook's program (±0.5 on leaving a cam) drifts and the axis hunts; past the last
cam it runs into the end stop (``axis stalled``). The drives are deterministic; the change of speed is the only
physics.

Stations: ``fork`` (a part put on the fork in front of the rack) and ``R11`` … ``R33`` (a place stocked before
the run). Events: ``part placed``, ``part removed``, ``part put down`` / ``part picked up`` (subject the place),
``part fell off`` (a part set down or lifted with the fork not far enough in), ``collision`` (subject ``rack``,
``data["what"]``) and the axes' ``axis stalled`` (an end stop), ``interlock violated`` (both directions of an axis),
``motor jammed``. The rig verb ``start_at`` puts an axis where the crane was left when it was switched off (before
the first scan). The axes' positions are traced in every row (``plant:X.s``, ``plant:Y.s``, ``plant:Z.s``).

>>> h = HBW()
>>> [k for k, v in h.sensors.items() if v]  # the crane at rest in front of place [1,1], fork at z2
['x1', 'y1', 'z2']
>>> _ = h.place("fork", part="p1")
>>> h.actuate("y_hore", True)
>>> while not h.sensors["y2"]:
...     h.step(1_000_000)
>>> h.actuate("y_hore", False); h.actuate("z_vpred", True)
>>> while not h.sensors["z3"]:
...     h.step(1_000_000)
>>> h.actuate("z_vpred", False); h.actuate("y_dole", True)
>>> while not h.sensors["y1"]:
...     h.step(1_000_000)
>>> [(e.kind, e.subject, e.part) for e in h.events]
[('part placed', 'fork', 'p1'), ('part put down', 'R11', 'p1')]
"""

from __future__ import annotations

from typing import Any

import numpy as np

from plants.components import draw
from plants.components.axis import Axis
from plants.components.component import Assembly
from plants.components.limit_switch import LimitSwitch
from plants.components.rack import TINE, Rack
from plants.components.sketch import Sketch
from plcsim.plant import (
    MOTOR_JAM,
    OBSERVABLES,
    PARTS,
    QUIESCENCE,
    SENSOR_SHIFT,
    Drawable,
    PlantEvent,
    RigVerb,
    SignalSpec,
    Station,
)

X_CAMS = {"x1": 100.0, "x2": 220.0, "x3": 340.0}
Y_CAMS = {"y1": 50.0, "y2": 70.0, "y3": 150.0, "y4": 170.0, "y5": 250.0, "y6": 270.0}
Z_CAMS = {"z1": -70.0, "z2": 0.0, "z3": 80.0}
SHELVES = (60.0, 160.0, 260.0)
X_ZONE, Y_ZONE, Z_ZONE = 6.0, 4.0, 4.0
TAU = 0.02
RACK_FRONT, RACK_DEPTH = 40.0, 80.0
PART = (40.0, 40.0, 30.0)
SIDE_X0 = 600.0  # where the side view (Z to the right) is drawn: z = 0 at x = SIDE_X0
ORDER = (*X_CAMS, *Y_CAMS, *Z_CAMS, "x_vpravo", "x_vlavo", "y_hore", "y_dole", "z_vpred", "z_vzad")
"""Fig. 4.161's order (%I0.0 x1 … %I1.3 z3, %Q0.0 x_vpravo … %Q0.5 z_vzad)."""

START_AT = RigVerb(
    "start_at",
    "start_at",
    "axis",
    "the crane was left with axis {target} at {mm} mm",
    targets="axes",
    doc="puts an axis at a position (mm, or a seeded (lo, hi) range) before the first scan: the crane's pose when "
    "it was switched on",
)


def _cams(positions: dict[str, float], zone: float, what: str) -> list[LimitSwitch]:
    return [
        LimitSwitch(n, p - zone, p + zone, doc=f"{what} cam {n}: True in [{p - zone:g}, {p + zone:g}] mm")
        for n, p in positions.items()
    ]


def _lamps(name: str, where: Any) -> tuple[Drawable, Drawable]:
    return (
        draw.polygon(f"cams/{name}/state", where, draw.BEAM_FREE),
        draw.polygon(f"cams/{name}/state", where, draw.BEAM_CUT),
    )


class HBW:
    """The stacker crane and its rack (see the module docstring)."""

    view = "side"
    CAPABILITIES = frozenset({PARTS, QUIESCENCE, OBSERVABLES, MOTOR_JAM, SENSOR_SHIFT})
    VERBS = {"start_at": START_AT}
    TRACED_OBSERVABLES = ("X.s", "Y.s", "Z.s")
    """The three axes' positions (mm), recorded in every trace row: the timing diagram draws them as lines."""

    def __init__(self, *, name: str = "HBW", seed: int = 0) -> None:
        self.name = name
        self.x = Axis(
            "X", 40.0, 400.0, start=100.0, speed=100.0, tau_s=TAU, plus="x_vpravo", minus="x_vlavo",
            cams=_cams(X_CAMS, X_ZONE, "column"),
            docs={"x_vpravo": "X right at 100 mm/s", "x_vlavo": "X left at 100 mm/s"},
        )  # fmt: skip
        self.y = Axis(
            "Y", 30.0, 290.0, start=50.0, speed=60.0, tau_s=TAU, plus="y_hore", minus="y_dole",
            cams=_cams(Y_CAMS, Y_ZONE, "height"),
            docs={"y_hore": "Y (the fork) up at 60 mm/s", "y_dole": "Y (the fork) down at 60 mm/s"},
        )  # fmt: skip
        self.z = Axis(
            "Z", -80.0, 90.0, start=0.0, speed=80.0, tau_s=TAU, plus="z_vpred", minus="z_vzad",
            cams=_cams(Z_CAMS, Z_ZONE, "depth"),
            docs={"z_vpred": "Z (the fork) forward, into the rack, at 80 mm/s", "z_vzad": "Z back at 80 mm/s"},
        )  # fmt: skip
        self.axes = {"X": self.x, "Y": self.y, "Z": self.z}
        self.rack = Rack(
            "rack", self.x, self.y, self.z, columns=tuple(X_CAMS.values()), shelves=SHELVES,
            front=RACK_FRONT, depth=RACK_DEPTH, part_size=PART,
        )  # fmt: skip
        self.assembly = Assembly([self.x, self.y, self.z, self.rack])
        specs = {s.name: s for s in self.assembly.specs()}
        self.signals: dict[str, SignalSpec] = {n: specs[n] for n in ORDER}
        self.EVENTS = self.assembly.events
        doc = "a place of the rack (stocked before the run): column {}, row {} (row 1 at the bottom)"
        self.stations = {"fork": Station("fork", SIDE_X0 - 60.0, 10.0, "on the fork, in front of the rack")} | {
            n: Station(n, X_CAMS[f"x{i}"], SHELVES[j - 1], doc.format(i, j)) for n, (i, j) in self.rack.places.items()
        }
        self._cam_lamps = [(cam, _lamps(cam.name, mark((cam.lo + cam.hi) / 2))) for axis, mark in (
            (self.x, lambda c: draw.rect(c - 3.0, -12.0, c + 3.0, -6.0)),
            (self.y, lambda c: draw.rect(SIDE_X0 - 111.0, c - 2.0, SIDE_X0 - 106.0, c + 2.0)),
            (self.z, lambda c: draw.rect(SIDE_X0 + c - 3.0, -12.0, SIDE_X0 + c + 3.0, -6.0)),
        ) for cam in axis.cams]  # fmt: skip
        """Each cam's lamp (off, on) under its axis, built once: a frame only picks one of the two."""
        self._crane_sketch, self._stored_sketch = Sketch(self._crane_drawn), Sketch(self._stored_drawn)
        """The crane (with the part it carries) and the stored parts, rebuilt only when they changed."""
        self.space: Any = None
        self.sensors: dict[str, Any] = {}
        self.events: list[PlantEvent] = []
        self.seed = seed
        self._ids = 0
        self.reset(seed=seed)

    # -- the protocol ---------------------------------------------------------------------------------------
    def reset(self, *, seed: int | None = None) -> None:
        """The crane at rest in front of [1,1] (x1, y1) with the fork at z2, the rack empty, time 0."""
        if seed is not None:
            self.seed = seed
        self.rng = np.random.default_rng(self.seed)
        self.now_ns = 0
        self._ids = 0
        self.events.clear()
        self.sensors.clear()
        self._pending: dict[str, bool] = {}
        for a, s in ((self.x, 100.0), (self.y, 50.0), (self.z, 0.0)):
            a.start = s
        self.assembly.reset(self)

    def emit(self, kind: str, subject: str, part: str | None = None, **data: Any) -> None:
        self.events.append(PlantEvent(self.now_ns, kind, subject, part, data))

    def wake(self, component: Any) -> None:
        self.assembly.wake(component)

    def actuate(self, name: str, value: Any) -> None:
        """A PLC output changed; the outputs of one scan are taken together at the start of the next step."""
        if not self.assembly.owns(name):
            raise KeyError(f"{self.name} has no actuator {name!r} (actuators: {', '.join(ORDER[12:])})")
        self._pending[name] = bool(value)

    def _commit(self) -> None:
        """Apply the commands of a scan: the ones switching off first, so that a reversal in one scan (R x_vlavo,
        S x_vpravo) is never taken for both directions at once."""
        pending, self._pending = self._pending, {}
        for name, value in sorted(pending.items(), key=lambda kv: kv[1]):
            self.assembly.actuate(self, name, value)

    def step(self, dt_ns: int) -> None:
        if dt_ns <= 0:
            raise ValueError(f"step: dt_ns must be > 0, not {dt_ns}")
        if self._pending:
            self._commit()
        self.now_ns += dt_ns
        if self.assembly.busy:
            self.assembly.advance(self, dt_ns / 1e9)
            self.rack.follow(self)

    def quiescent(self) -> bool:
        """True while no axis moves and no command waits."""
        return not self.assembly.busy and not self._pending

    def jam_motor(self, name: str, jammed: bool) -> None:
        """Fault: an axis's drive (``X`` or one of its outputs) does not move it."""
        self.assembly.jam(self, name, jammed)

    def shift_sensor(self, name: str, dx_mm: float) -> None:
        """Fault: a cam mounted ``dx_mm`` off its place."""
        self.assembly.shift(self, name, dx_mm)

    def start_at(self, target: str, mm: float | tuple[float, float]) -> None:
        """The rig verb ``start_at``: axis ``target`` stands at ``mm`` (or a seeded draw from a ``(lo, hi)`` range)."""
        axis = self.axes[target]
        s = float(self.rng.uniform(*mm)) if isinstance(mm, tuple | list) else float(mm)
        if not axis.lo <= s <= axis.hi:
            raise ValueError(f"start_at {target}: {s:g} mm is outside the axis's travel [{axis.lo:g}, {axis.hi:g}]")
        if any(axis.command.values()) or any(self._pending.get(a) for a in (axis.plus, axis.minus)):
            raise ValueError(f"start_at {target}: the axis is driven; a pose is set before the first scan")
        axis.start = s
        axis.reset(self)
        self.rack.reset_pose()

    def event_subjects(self) -> set[str]:
        return self.assembly.subjects()

    # -- parts ----------------------------------------------------------------------------------------------
    def place(
        self, station: str, *, part: str | None = None, offset_mm: float = 0.0, angle_deg: float = 0.0, **_: Any
    ) -> str:
        """Put a part on the fork (in front of the rack) or on a place of the rack; the pose error is taken up by
        the fork's and the shelf's guides (a part always sits centred)."""
        if part is None:
            self._ids += 1
            part = f"p{self._ids}"
        if station == "fork":
            self.rack.put_on_fork(self, part)
        elif station in self.rack.places:
            self.rack.stock(self, station, part)
        else:
            raise KeyError(f"{self.name} has no station {station!r} (stations: {', '.join(self.stations)})")
        return part

    def remove(self, target: str) -> None:
        self.rack.take(self, target)

    # -- observables ----------------------------------------------------------------------------------------
    def observables(self) -> dict[str, float]:
        """The axes' positions (mm) and speeds (mm/s)."""
        out = {f"{n}.s": a.s for n, a in self.axes.items()}
        out |= {f"{n}.v": a.v for n, a in self.axes.items()}
        return out

    def sample_observables(self) -> tuple[float, ...]:
        return (self.x.s, self.y.s, self.z.s)

    # -- drawing: the front view (X right, Y up) and, right of it, the side view (Z right, Y up) -------------
    def bounds(self) -> tuple[float, float, float, float]:
        return (-10.0, -40.0, SIDE_X0 + RACK_FRONT + RACK_DEPTH + 40.0, 360.0)

    def static_drawables(self) -> list[Drawable]:
        out = [
            draw.polygon("floor", draw.rect(0.0, -4.0, SIDE_X0 + 170.0, 0.0), draw.FRAME),
            draw.label("views/front", 220.0, 345.0, "front view (X, Y)"),
            draw.label("views/side", SIDE_X0, 345.0, "side view (Z, Y)"),
        ]
        half = 60.0
        for i, (name, cx) in enumerate(X_CAMS.items(), start=1):  # the rack seen from the front
            out.append(draw.polygon(f"rack/post{i}", draw.rect(cx - half, 0.0, cx - half + 6.0, 300.0), draw.FRAME))
            for j, top in enumerate(SHELVES, start=1):
                out.append(draw.polygon(f"rack/R{i}{j}", draw.rect(cx - half, top - 8.0, cx + half, top), draw.FRAME))
            out.append(draw.label(f"cams/{name}", cx, -22.0, name))
        out.append(draw.polygon("rack/post4", draw.rect(400.0 - 6.0, 0.0, 400.0, 300.0), draw.FRAME))
        for j in range(1, 4):
            out.append(draw.label(f"rack/row{j}", 22.0, SHELVES[j - 1] + 22.0, f"row {j}"))
        for k, (name, h) in enumerate(Y_CAMS.items()):  # Y cams on the side view's mast; odd and even apart
            x = SIDE_X0 - (135.0 if k % 2 else 185.0)
            out.append(draw.line(f"cams/{name}/mark", [(x + 10.0, h), (SIDE_X0 - 119.0, h)], draw.TEXT))
            out.append(draw.label(f"cams/{name}", x, h, name))
        z0, z1 = SIDE_X0 + RACK_FRONT, SIDE_X0 + RACK_FRONT + RACK_DEPTH
        out.append(draw.polygon("side/rack", draw.rect(z1, 0.0, z1 + 6.0, 300.0), draw.FRAME))
        for j, top in enumerate(SHELVES, start=1):
            out.append(draw.polygon(f"side/shelf{j}", draw.rect(z0, top - 8.0, z1, top), draw.FRAME))
        for name, z in Z_CAMS.items():
            out.append(draw.label(f"cams/{name}", SIDE_X0 + z, -22.0, name))
        out.append(draw.polygon("side/mast", draw.rect(SIDE_X0 - 118.0, 0.0, SIDE_X0 - 112.0, 300.0), draw.BELT))
        return out

    def dynamic_drawables(self) -> list[Drawable]:
        x, y, z, rack = self.x, self.y, self.z, self.rack
        crane = self._crane_sketch((x.s, y.s, z.s, bool(x.v), bool(y.v), bool(z.v), rack.on_fork))
        out = crane[:4]
        out += [lamps[cam.actuated] for cam, lamps in self._cam_lamps]
        out += self._stored_sketch((tuple(rack.stored.items()), rack.column_at()))
        out += crane[4:]
        return out

    def _crane_drawn(self) -> list[Drawable]:
        """The mast, the fork (front and side view) and the part on the fork: four shapes, then the part's two."""
        x, y, z = self.x.s, self.y.s, self.z.s
        w, d, h = PART
        moving = draw.BELT_RUNNING
        out = [
            draw.polygon("crane/mast", draw.rect(x - 4.0, 0.0, x + 4.0, 300.0), moving if self.x.v else draw.BELT),
            draw.polygon("crane/fork", draw.rect(x - 26.0, y - TINE, x + 26.0, y), moving if self.y.v else draw.BELT),
            draw.polygon(
                "side/fork", draw.rect(SIDE_X0 + z - d / 2 - 5.0, y - TINE, SIDE_X0 + z + d / 2 + 5.0, y),
                moving if self.z.v or self.y.v else draw.BELT,
            ),
            draw.line("side/arm", [(SIDE_X0 - 112.0, y - 3.0), (SIDE_X0 + z - d / 2 - 5.0, y - 3.0)], draw.BELT),
        ]  # fmt: skip
        if self.rack.on_fork is not None:  # named in the side view: in the front view it passes over stored parts
            part = self.rack.on_fork
            out.append(draw.polygon(f"parts/{part}", draw.rect(x - w / 2, y, x + w / 2, y + h), draw.PART_HELD))
            zc = SIDE_X0 + z
            side = draw.rect(zc - d / 2, y, zc + d / 2, y + h)
            out.append(draw.polygon(f"side/parts/{part}", side, draw.PART_HELD, part))
        return out

    def _stored_drawn(self) -> list[Drawable]:
        """The parts on the rack's places, and in the side view those of the column the crane stands at."""
        w, d, h = PART
        out = []
        col = self.rack.column_at()
        for (i, j), part in sorted(self.rack.stored.items()):
            cx, top = X_CAMS[f"x{i}"], SHELVES[j - 1]
            out.append(draw.polygon(f"parts/{part}", draw.rect(cx - w / 2, top, cx + w / 2, top + h), draw.PART, part))
            if i == col:  # the side view shows the column the crane stands at
                zc = SIDE_X0 + RACK_FRONT + RACK_DEPTH / 2
                side = draw.rect(zc - d / 2, top, zc + d / 2, top + h)
                out.append(draw.polygon(f"side/parts/{part}", side, draw.PART))
        return out
