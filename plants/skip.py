"""SKIP (4.3.16): a skip hoist — a bucket on an inclined track, pulled up by a rope winch through a frequency
converter, tipping on the curved top of the track into a concrete mixer.

Side view, y up, mm; ``s`` is the skip's position along the track (0 = the bottom sensor's centre). The parameters
are **variant A** of ``spec/exercises.md`` §5.7, chosen because it is the one in which the textbook's words hold:
"measure the travel time with a full skip and add a small reserve; let it be 32 s". A full skip climbs in ≈ 28.6 s
(32 s leaves ≈ 12 %), and the slow descent of the empty skip takes ≈ 39.4 s, for which the same rule gives a down
alarm of **45 s** (≈ 14 %), the time the exercise states. In variant B (80/40 mm/s) one 32 s constant fits both
directions, but only because it is twice the ascent: no "small reserve" for the travel the textbook times. Variant
A also keeps the textbook's warning alive: manual travel is slow everywhere, and a full manual ascent (≈ 40.6 s)
outlasts 32 s.

* track inclined 60°, bottom sensor ``SNIMAC_DOLNY`` at 0, slow-down sensor ``SNIMAC_SPOMAL`` at 800, top sensor
  ``SNIMAC_HORNY`` at 1000 mm, each a cam switch 20 mm long (``[c-10, c+10]``, hysteresis 0.5 mm), all True while
  actuated; end buffers at −25 and +1030 mm (``end stop hit``, with the speed of the impact);
* the winch (:class:`~plants.components.winch.Winch`) through the converter: ``START_HORE`` / ``START_DOLE`` the
  direction, ``RYCHLOST_RYCHLO`` 50 Hz = 40 mm/s, ``RYCHLOST_POMALY`` 31.25 Hz = 25 mm/s (both: fast), ramps
  100 Hz/s (0 → fast 0.5 s, fast → slow 0.19 s), brake held whenever no direction is active (250 mm/s²: a skip
  stopped at a sensor from the slow speed stands 1.25 mm past its edge); both directions: ``converter fault``; a
  direction without a speed bit: 0 Hz, brake held, ``converter warning``; a full skip runs 3 % slow going up;
* the bucket (:class:`~plants.components.bucket.Bucket`): tilt 0° at 900 mm rising to 120° at 1000 mm on the curved
  top rails; its 200 g of aggregate start to pour at 90° (975 mm) and pour at 80 g/s from 105° (987.5 mm) on, all
  into the mixer: a skip stopped at the top sensor is empty ≈ 2.1 s later, well inside the 6 s dump;
  ``pour ended`` reports the share of the batch that reached the mixer;
* ``speed measured`` at each sensor as it makes (the arrival speed at the top: slow, or fast with a dead
  slow-down sensor).

Verbs of the rig: ``fill`` (the dosing hopper fills the skip at the bottom — what the operator's PLNY reports) and
``discharge`` (the mixer empties its batch — after which it allows aggregate again). The faults: ``jam_motor``
(rope jam / overload: the skip stands), ``shift_sensor``, and the wiring's stuck sensors.

Nominal figures at dt = 1 ms (``tests/rigs/test_skip_plant.py``): full skip bottom → top ≈ 28.6 s (SPOMAL after 20.4 s),
empty skip top → bottom at the slow speed ≈ 39.4 s, a full manual (slow) ascent ≈ 40.6 s; the skip stopped at the
top sensor is empty ≈ 2.1 s after it arrived.

>>> p = Skip()
>>> p.fill("skip")
>>> for out in ("START_HORE", "RYCHLOST_RYCHLO"): p.actuate(out, True)
>>> while not p.sensors["SNIMAC_HORNY"]:
...     p.step(1_000_000)
>>> round(p.now_ns / 1e9, 1), [(e.subject, e.data["speed_mm_s"]) for e in p.events if e.kind == "speed measured"]
(25.5, [('SNIMAC_SPOMAL', 38.8), ('SNIMAC_HORNY', 38.908)])
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from plants.components import draw
from plants.components.bucket import Bucket
from plants.components.component import Assembly
from plants.components.limit_switch import LimitSwitch
from plants.components.sketch import Sketch
from plants.components.winch import Winch
from plcsim.plant import MOTOR_JAM, OBSERVABLES, QUIESCENCE, SENSOR_SHIFT, Drawable, PlantEvent, RigVerb, SignalSpec

ANGLE = math.radians(60.0)
U = (math.cos(ANGLE), math.sin(ANGLE))  # along the track, up
N = (-math.sin(ANGLE), math.cos(ANGLE))  # across it, to the upper-left side
ORIGIN = (0.0, 40.0)  # the bottom sensor's centre in the drawing
SENSORS = {"SNIMAC_DOLNY": 0.0, "SNIMAC_SPOMAL": 800.0, "SNIMAC_HORNY": 1000.0}
CAM_HALF = 10.0
LABEL_SHIFT = {"SNIMAC_DOLNY": 80.0, "SNIMAC_SPOMAL": -40.0, "SNIMAC_HORNY": -60.0}
STATE_X = 90.0  # where the VFD, skip and mixer states are written (mm)
"""Each sensor's label sits this far along the track from it (clear of the pouring stream), on the right side."""
BUFFERS = (-25.0, 1030.0)
V_FAST, V_SLOW = 40.0, 25.0  # mm/s, variant A of §5.7
TIP_FROM, TIP_TO = 900.0, 1000.0
START = 8.5  # where a skip stopped at the bottom sensor from the slow speed stands
LOADING_ZONE = 15.0  # the hopper fills the skip within this distance of the bottom sensor's centre
MIXER = (680.0, 840.0, 640.0, 780.0)  # x0, x1, y0, y1 of the mixer drum
WIDTH, DEPTH = 120.0, 80.0  # the bucket, drawn
MIXER_CAPACITY_G = 1000.0

FILL = RigVerb(
    "fill",
    "fill",
    "skip",
    "fill {target}",
    targets="skips",
    state=True,
    doc="the dosing hopper fills the skip with a 200 g batch of aggregate (only at the bottom)",
)
DISCHARGE = RigVerb(
    "discharge",
    "discharge",
    "mixer",
    "discharge {target}",
    targets="mixers",
    doc="the mixer empties its batch",
)


def at(s: float, across: float = 0.0) -> tuple[float, float]:
    """The drawing point ``s`` mm along the track and ``across`` mm to its upper-left side."""
    return (ORIGIN[0] + s * U[0] + across * N[0], ORIGIN[1] + s * U[1] + across * N[1])


def _bucket_frame(s: float, tilt: float) -> tuple[float, float, float, float]:
    """The bucket's own frame (origin: its front bottom corner, level when untilted) with the skip at ``s`` and the
    bucket turned forward by ``tilt`` degrees about that corner: the origin's drawing point, cos and sin of the turn."""
    px, py = at(s + 30.0, 6.0)
    a = math.radians(-tilt)
    return (px, py, math.cos(a), math.sin(a))


def _in_frame(frame: tuple[float, float, float, float], x: float, y: float) -> tuple[float, float]:
    """The drawing point of ``(x, y)`` in the bucket's frame (:func:`_bucket_frame`)."""
    px, py, c, sn = frame
    return (px + x * c - y * sn, py + x * sn + y * c)


def _turned(s: float, tilt: float, x: float, y: float) -> tuple[float, float]:
    """The drawing point ``(x, y)`` of the bucket's own frame with the skip at ``s`` and the bucket turned by
    ``tilt`` degrees (:func:`_bucket_frame`)."""
    return _in_frame(_bucket_frame(s, tilt), x, y)


def _lamps(name: str, c: float) -> tuple[Drawable, Drawable]:
    """Sensor ``name``'s cam at ``c`` mm along the track: (free, actuated)."""
    corners = [at(c - CAM_HALF, -10.0), at(c + CAM_HALF, -10.0), at(c + CAM_HALF, -18.0), at(c - CAM_HALF, -18.0)]
    return (
        draw.polygon(f"sensors/{name}", corners, draw.BEAM_FREE),
        draw.polygon(f"sensors/{name}", corners, draw.BEAM_CUT),
    )


class Skip:
    """The skip hoist (see the module docstring)."""

    view = "side"
    CAPABILITIES = frozenset({QUIESCENCE, OBSERVABLES, MOTOR_JAM, SENSOR_SHIFT})
    VERBS = {"fill": FILL, "discharge": DISCHARGE}
    TRACED_OBSERVABLES = ("skip.s", "skip.v")
    """The skip's position (mm along the track) and speed (mm/s) in every trace row (``plant:skip.s``, ``.v``)."""

    def __init__(self, *, name: str = "SKIP", seed: int = 0) -> None:
        self.name = name
        cams = [
            LimitSwitch(
                n, c - CAM_HALF, c + CAM_HALF, doc=f"cam switch at {c:g} mm along the track: True while actuated"
            )
            for n, c in SENSORS.items()
        ]
        self.winch = Winch(
            "skip",
            *BUFFERS,
            start=START,
            v_fast=V_FAST,
            v_slow=V_SLOW,
            up="START_HORE",
            down="START_DOLE",
            fast="RYCHLOST_RYCHLO",
            slow="RYCHLOST_POMALY",
            cams=cams,
            converter="VFD",
        )
        self.bucket = Bucket("skip", "mixer", tip_from=TIP_FROM, tip_to=TIP_TO)
        self.skips = {"skip": self.bucket}
        self.mixers = {"mixer": self.bucket}
        self.assembly = Assembly([self.winch, self.bucket])
        self._cam_lamps = {n: _lamps(n, c) for n, c in SENSORS.items()}
        """Each sensor's cam (free, actuated), built once: a frame only picks one of the two."""
        self._skip_sketch, self._mixer_sketch = Sketch(self._skip_drawn), Sketch(lambda: self._mixer(self.bucket))
        """The skip and the mixer's load, rebuilt only when they changed (a standing skip is drawn once)."""
        self._labels: dict[str, Drawable] = {}
        """The state labels last drawn, by path: one is built again only when its text changed."""
        specs = {s.name: s for s in self.assembly.specs()}
        order = ("SNIMAC_DOLNY", "SNIMAC_HORNY", "SNIMAC_SPOMAL", "START_HORE", "START_DOLE")
        self.signals: dict[str, SignalSpec] = {n: specs[n] for n in (*order, "RYCHLOST_POMALY", "RYCHLOST_RYCHLO")}
        self.EVENTS = self.assembly.events
        self.space: Any = None
        self.sensors: dict[str, Any] = {}
        self.events: list[PlantEvent] = []
        self.seed = seed
        self.reset(seed=seed)

    # --- the protocol --------------------------------------------------------------------------------------
    def reset(self, *, seed: int | None = None) -> None:
        """The empty skip at rest at the bottom sensor, the converter off, the mixer empty, time 0."""
        if seed is not None:
            self.seed = seed
        self.rng = np.random.default_rng(self.seed)
        self.now_ns = 0
        self.events.clear()
        self.sensors.clear()
        self.assembly.reset(self)
        self.bucket.position = self.winch.s
        self.winch.load = 0.0

    def emit(self, kind: str, subject: str, part: str | None = None, **data: Any) -> None:
        self.events.append(PlantEvent(self.now_ns, kind, subject, part, data))

    def wake(self, component: Any) -> None:
        self.assembly.wake(component)

    def actuate(self, name: str, value: Any) -> None:
        if not self.assembly.owns(name):
            actuators = [n for n, spec in self.signals.items() if spec.direction == "actuator"]
            raise KeyError(f"{self.name} has no actuator {name!r} (actuators: {', '.join(actuators)})")
        self.assembly.actuate(self, name, value)

    def step(self, dt_ns: int) -> None:
        if dt_ns <= 0:
            raise ValueError(f"step: dt_ns must be > 0, not {dt_ns}")
        self.now_ns += dt_ns
        dt = dt_ns / 1e9
        winch, bucket = self.winch, self.bucket
        if self.assembly.busy:
            self.assembly.advance(self, dt)
            bucket.position = winch.s
        if bucket.pouring_possible():
            bucket.advance(self, dt)
            winch.load = bucket.load_g / bucket.capacity

    def quiescent(self) -> bool:
        """True while the skip stands (brake held) and nothing pours."""
        return not self.assembly.busy and not self.bucket.pouring_possible()

    def event_subjects(self) -> set[str]:
        return self.assembly.subjects()

    def observables(self) -> dict[str, float]:
        """Position (mm), speed (mm/s), converter frequency (Hz), tilt (°), the load and the mixer's mass (g)."""
        w, b = self.winch, self.bucket
        return {
            "skip.s": w.s,
            "skip.v": w.v,
            "VFD.f": w.f,
            "skip.tilt": b.tilt,
            "skip.load_g": b.load_g,
            "mixer.g": b.bin_g,
        }

    def sample_observables(self) -> tuple[float, ...]:
        return (self.winch.s, self.winch.v)

    # --- faults and verbs ----------------------------------------------------------------------------------
    def jam_motor(self, name: str, jammed: bool) -> None:
        """Fault: the rope jams (``name``: ``skip``, ``VFD`` or one of the converter's outputs); the skip stands."""
        if name == "VFD":
            name = "skip"
        if not self.assembly.has(name) or name in self.sensors:
            raise KeyError(f"{self.name}: no drive {name!r} to jam (the winch: skip, START_HORE, START_DOLE ...)")
        self.assembly.jam(self, name, jammed)

    def shift_sensor(self, name: str, dx_mm: float) -> None:
        """Fault: a cam switch mounted ``dx_mm`` off its place (+ = up the track)."""
        if name not in SENSORS:
            raise KeyError(f"{self.name} has no sensor {name!r} (sensors: {', '.join(SENSORS)})")
        self.assembly.shift(self, name, dx_mm)

    def fill(self, name: str) -> None:
        """Verb ``fill``: the dosing hopper fills the skip — only where it stands under the hopper (the bottom)."""
        if abs(self.winch.s - SENSORS["SNIMAC_DOLNY"]) > LOADING_ZONE:
            raise ValueError(f"the skip is at {self.winch.s:.0f} mm, not under the dosing hopper at the bottom")
        self.skips[name].fill(self)
        self.winch.load = self.bucket.load_g / self.bucket.capacity

    def discharge(self, name: str) -> None:
        """Verb ``discharge``: the mixer empties its batch."""
        self.mixers[name].discharge(self)

    # --- drawing -------------------------------------------------------------------------------------------
    def bounds(self) -> tuple[float, float, float, float]:
        return (-200.0, -20.0, 900.0, 1200.0)

    def static_drawables(self) -> list[Drawable]:
        lo, hi = BUFFERS
        rails = [
            draw.line(f"track/rail{k}", [at(lo - 20.0, a), at(hi + 15.0, a)], draw.FRAME)
            for k, a in ((1, 0.0), (2, -6.0))
        ]
        buffers = [
            draw.polygon(
                "track/buffer_bottom",
                [at(lo - 14.0, 8.0), at(lo, 8.0), at(lo, -14.0), at(lo - 14.0, -14.0)],
                draw.END_STOP,
            ),
            draw.polygon(
                "track/buffer_top",
                [at(hi, 8.0), at(hi + 14.0, 8.0), at(hi + 14.0, -14.0), at(hi, -14.0)],
                draw.END_STOP,
            ),
        ]
        x0, x1, y0, y1 = MIXER
        mixer = [
            draw.polygon("mixer/legs", draw.rect(x0 + 50.0, 0.0, x1 - 50.0, y0), (205, 205, 210)),
            draw.polygon("mixer/drum", [(x0, y1), (x1, y1), (x1 - 18.0, y0), (x0 + 18.0, y0)], draw.FRAME),
            draw.label("mixer/label", x1 - 45.0, y0 - 30.0, "mixer"),
        ]
        hopper = [
            draw.polygon("hopper", [(-130.0, 300.0), (10.0, 300.0), (-40.0, 220.0), (-80.0, 220.0)], draw.FRAME),
            draw.label("hopper/label", -60.0, 330.0, "dosing hopper"),
        ]
        labels = [draw.label(f"sensors/{n}/label", *at(c + LABEL_SHIFT[n], -120.0), n) for n, c in SENSORS.items()]
        leaders = [
            draw.line(f"sensors/{n}/leader", [at(c, -20.0), at(c + LABEL_SHIFT[n], -100.0)], draw.FRAME)
            for n, c in SENSORS.items()
        ]
        winch = [
            draw.circle("winch/sheave", *at(hi + 30.0, 8.0), 10.0, draw.BELT),
            draw.polygon("winch/house", draw.rect(120.0, 1040.0, 220.0, 1100.0), draw.BELT),
            draw.label("winch/label", 170.0, 1130.0, "winch"),
        ]
        ground = draw.line("ground", [(-200.0, 0.0), (900.0, 0.0)], draw.TEXT)
        return [ground, *rails, self._tipping_rail(), *buffers, *mixer, *hopper, *leaders, *labels, *winch]

    def _tipping_rail(self) -> Drawable:
        """The curved top rail that turns the bucket over: the path of the bucket's rear corner from 900 mm on."""
        lo = self.bucket.tip_from
        points = [_turned(lo + k * 10.0, self.bucket.tilt_at(lo + k * 10.0), -WIDTH, 0.0) for k in range(14)]
        return draw.line("track/tipping_rail", points, draw.FRAME)

    def dynamic_drawables(self) -> list[Drawable]:
        w, b = self.winch, self.bucket
        out = [self._cam_lamps[n][bool(self.sensors[n])] for n in SENSORS]
        phase = (self.now_ns / 1e9 * 4.0) % 1.0 if b.flow_g_s > 0.0 else None  # the pouring stream flows on
        out += self._skip_sketch((w.s, b.position, b.load_g, b.flow_g_s, phase))
        out += self._mixer_sketch(b.bin_g)
        state = "fault" if w.fault else "jammed" if w.jammed else "brake" if w.braked else f"{abs(w.f):.1f} Hz"
        arrow = " up" if w.f > 0 else " down" if w.f < 0 else ""
        # the state in the empty room left of the rail, centred (a recording centres a text on its point), 70 mm
        # apart: at the scale a recording draws this tall rig, a line of text is 60 mm high
        out.append(self._label("VFD/state", 880.0, f"VFD: {state}{arrow}, {abs(w.v):.1f} mm/s"))
        out.append(self._label("skip/state", 810.0, f"skip: {b.load_g:.0f} g at {w.s:.0f} mm"))
        out.append(self._label("mixer/mass", 740.0, f"mixer: {b.bin_g:.0f} g"))
        return out

    def _label(self, path: str, y: float, text: str) -> Drawable:
        """The state label ``path`` at height ``y`` saying ``text`` (the one drawn last if it said the same)."""
        d = self._labels.get(path)
        if d is None or d.text != text:
            d = self._labels[path] = draw.label(path, STATE_X, y, text)
        return d

    def _skip_drawn(self) -> list[Drawable]:
        """The rope and the skip where they are now."""
        s = self.winch.s
        rope = draw.line("winch/rope", [at(s + 30.0, 10.0), at(BUFFERS[1] + 30.0, 18.0), (170.0, 1070.0)], (90, 90, 90))
        return [rope, *self._bucket(s, self.bucket)]

    def _bucket(self, s: float, b: Bucket) -> list[Drawable]:
        """The car on the rails and the bucket on it, turned about its front bottom corner by the tilt, with its
        load and the pouring stream."""
        base = _turned(s, 0.0, 0.0, 0.0)
        frame = _bucket_frame(s, b.tilt)
        car = [base, at(s - 70.0, 6.0), (base[0] - WIDTH, base[1])]
        body = [_in_frame(frame, x, y) for x, y in ((0.0, 0.0), (0.0, DEPTH), (-WIDTH, DEPTH), (-WIDTH, 0.0))]
        out = [draw.polygon("skip/car", car, draw.BELT), draw.polygon("skip/bucket", body, (110, 110, 125))]
        share = b.load_g / b.capacity
        if share > 0.0:
            top = 4.0 + (DEPTH - 8.0) * min(1.0, share)
            corners = ((-4.0, 4.0), (-4.0, top), (4.0 - WIDTH, top), (4.0 - WIDTH, 4.0))
            out.append(draw.polygon("skip/load", [_in_frame(frame, x, y) for x, y in corners], draw.PART))
        if b.flow_g_s > 0.0:
            x0, y0 = _in_frame(frame, 0.0, DEPTH)
            tx, ty = (MIXER[0] + MIXER[1]) / 2, MIXER[3] - 10.0
            phase = (self.now_ns / 1e9 * 4.0) % 1.0
            n = max(2, round(12 * b.flow_g_s / b.rate))
            for k in range(n):
                u = (k + phase) / n
                out.append(draw.circle(f"skip/pour/{k}", x0 + (tx - x0) * u, y0 + (ty - y0) * u * u, 5.0, draw.PART))
        return out

    def _mixer(self, b: Bucket) -> list[Drawable]:
        x0, x1, y0, y1 = MIXER
        level = y0 + 4.0 + (y1 - y0 - 8.0) * min(1.0, b.bin_g / MIXER_CAPACITY_G)
        out = []
        if b.bin_g > 0.0:
            out.append(draw.polygon("mixer/load", draw.rect(x0 + 22.0, y0 + 4.0, x1 - 22.0, level), draw.PART))
        return out
