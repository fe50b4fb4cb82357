"""PUNCH (6.3.1–6.3.5): "Punching Machine with Conveyor Belt 24V – Education" — a reversible belt and a press.

Side view, y up, mm. Parameters are the proposals of ``spec/exercises.md`` §5.10 (changes are listed below):

* belt ``M1``, 280 mm, top surface 50 mm above the base, 40 mm/s forward (``M1_VPRED``, towards the press) and
  backward (``M1_VZAD``, towards the loading end), first-order drive τ = 50 ms, μ = 0.6; both ends open (a part
  carried past either end falls off);
* light barriers ``OS1`` at 45 mm and ``OS2`` at 230 mm, 10 mm above the belt, spot 2 mm (True = interrupted; the
  textbook wires both NC);
* press ``M2`` over the belt at x = 215 mm (:class:`~plants.components.press.Press`, a component on a 1-D
  :class:`~plants.components.axis.Axis`): ``M2_DOLE`` drives it down, ``M2_HORE`` up, 25 mm/s, τ = 20 ms; the tool
  tip rests at 105.5 mm at the top and stops ≈ 71.5 mm at the bottom (the part's top is at 70 mm); limit switches
  **KS1 = upper** (make point 105 mm) and **KS2 = lower** (72 mm), as all the textbook's solutions use them;
  ``ks1="lower"`` swaps the names, as the model text reads (text issue 12); mechanical end stops 3 mm beyond each
  switch, where a driven ram stalls (``axis stalled``).

Stations: ``OS1`` (a part centred on the OS1 beam: the loading place) and ``OS2`` (a part put straight under the
press, centred 5 mm downstream of the press axis so that, with the operator's ±5 mm, it always cuts the OS2 beam).

Events besides the belt line's:

* ``press stroke``: the tip passed 75 mm going down; ``part`` = the part whose extent contains the press axis (or
  none), ``data["offset_mm"]`` = its centre's distance from the axis;
* ``axis stalled``: the press is driven against an end stop (``data["end"]`` = ``lo`` at the top, ``hi`` at the
  bottom) or onto a part (``part damaged`` follows); ``motor jammed``: the fault ``jam_motor("M2_DOLE")``;
* ``part damaged``: a part moved under the lowered tool, or the ram was driven into it;
* ``interlock violated`` (subject ``M1`` or ``M2``, ``data["reason"]``): both directions of M1 or of M2 commanded
  (the motor then stops), the belt driven while the press is away from the top, the press driven while the belt
  is driven.

The rig is an assembly of components (:mod:`plants.components.side_view`): the two beams, the belt
(:class:`~plants.components.belt.Belt`) and the press. Commands are taken at the start of the next physics step,
all outputs of a scan together, so the order in which one scan's outputs reach the plant never makes a violation
(``R M1_VZAD`` and ``S M1_VPRED`` in one scan reverse the belt cleanly; the press does the same for its two relays).
The tool tip height is traced in every row as the analog column ``plant:M2.z`` (``TRACED_OBSERVABLES``), so a
timing diagram draws the ram's strokes as a line under KS1/KS2.

Nominal figures, measured at dt = 1 ms by ``tests/rigs/test_punch_plant.py`` (§5.10 in brackets): OS1 → OS2 forward
with the part placed centred on OS1 ≈ 4.28 s (4.3 s); OS2 → OS1 return ≈ 3.9 s (3.9 s); one stroke KS1 → KS2 → KS1
≈ 2.7 s (2.7 s). Changes to §5.10: the returning part is stopped by its *leading* (left) face, so it rests
spanning ≈ 44–74 mm, not 14–44 mm (§5.10 counted the trailing face); the tip's rest heights are 105.5 / 71.5 mm
(the 0.5 mm coast of the drive past each switch's make point).

>>> p = Punch()
>>> pid = p.place("OS1", offset_mm=0.0)
>>> p.actuate("M1_VPRED", True)
>>> while not p.sensors["OS2"]:
...     p.step(1_000_000)
>>> p.actuate("M1_VPRED", False)
>>> p.actuate("M2_DOLE", True)
>>> while not p.sensors["KS2"]:
...     p.step(1_000_000)
>>> [(e.kind, e.part) for e in p.events if e.kind == "press stroke"]
[('press stroke', 'p1')]
"""

from __future__ import annotations

from collections.abc import Iterator

from plants.components import draw
from plants.components.belt import Belt
from plants.components.light_barrier import LightBarrier
from plants.components.press import PartUnder, Press
from plants.components.side_view import SideViewPlant
from plcsim.plant import Drawable, Station

TOP = 50.0  # belt surface above the base, mm
LENGTH = 280.0
SPEED = 40.0  # mm/s
OS1_X, OS2_X = 45.0, 230.0
PRESS_X = 215.0
BEAM_HEIGHT = 10.0
FORWARD, BACKWARD = "M1_VPRED", "M1_VZAD"


class Punch(SideViewPlant):
    """The punching machine with its reversible belt (see the module docstring).

    Args:
        ks1: ``upper`` (KS1 is the upper limit switch, as the textbook's solutions use it) or ``lower`` (the model
            text's reading).
        name, seed: as every rig.
    """

    TRACED_OBSERVABLES = ("M2.z",)
    """The ram's tool tip height (mm) is recorded in every trace row, as column ``plant:M2.z``."""

    def __init__(self, *, ks1: str = "upper", name: str = "PUNCH", seed: int = 0) -> None:
        if ks1 not in ("upper", "lower"):
            raise ValueError(f"{name}: ks1 must be 'upper' or 'lower', not {ks1!r}")
        self.ks1 = ks1
        upper, lower = ("KS1", "KS2") if ks1 == "upper" else ("KS2", "KS1")
        self.press = Press("M2", parts_under=self._parts_under, x=PRESS_X, upper=upper, lower=lower)
        self.belt = Belt(
            "M1",
            0.0,
            LENGTH,
            TOP,
            speed=SPEED,
            tau_s=0.05,
            friction=0.6,
            forward=FORWARD,
            backward=BACKWARD,
            docs={
                FORWARD: f"belt M1 forward (towards the press) at {SPEED:g} mm/s while True",
                BACKWARD: f"belt M1 backward (towards OS1) at {SPEED:g} mm/s while True",
            },
        )
        beam = f"{BEAM_HEIGHT:g} mm above the belt: True while interrupted"
        barriers = [
            LightBarrier(
                "OS1", OS1_X, TOP + BEAM_HEIGHT, doc=f"light barrier at the loading place, {OS1_X:g} mm, {beam}"
            ),
            LightBarrier("OS2", OS2_X, TOP + BEAM_HEIGHT, doc=f"light barrier under the press, {OS2_X:g} mm, {beam}"),
        ]
        stations = [
            Station("OS1", OS1_X, TOP, "the loading place: a part centred on the OS1 beam"),
            Station("OS2", PRESS_X + 5.0, TOP, "under the press: a part centred 5 mm past the press axis cuts OS2"),
        ]
        self._axis, self._upper, self._z0 = self.press.axis, self.press.upper, self.press.z0
        super().__init__(name, components=[*barriers, self.belt, self.press], stations=stations, seed=seed)

    # --- lifecycle -----------------------------------------------------------------------------------------------
    def reset(self, *, seed: int | None = None) -> None:
        """As every side-view rig (the press at rest at the top, its motor off), no interlock violated."""
        super().reset(seed=seed)
        self._violations: set[tuple[str, str]] = set()
        self._at_top = True

    def step(self, dt_ns: int) -> None:
        """Take the new commands, advance belt, press and parts, then look at the interlocks."""
        if dt_ns > self.max_step_ns or dt_ns <= 0:
            self._step_split(dt_ns)
            return
        press, upper = self.press, self._upper
        changed = press.pending or bool(self._deferred)
        if self.belt.v != 0.0 and self._axis.s >= press.s_reach:  # a part may be carried under the lowered tool
            self.wake(press)
        SideViewPlant.step(self, dt_ns)
        if changed or upper.actuated != self._at_top:
            self._at_top = upper.actuated
            self._check_interlocks()

    def _check_interlocks(self) -> None:
        """Belt and press must not move together: each violation is logged once, when it begins."""
        belt_on = any(self.belt.commands.values())
        active = set()
        if belt_on and not self.press.at_top:
            active.add((self.belt.name, "belt driven while the press is away from the top"))
        if belt_on and self.press.driven:
            active.add((self.press.name, "press driven while the belt is driven"))
        for subject, reason in sorted(active - self._violations):
            self.emit("interlock violated", subject, reason=reason)
        self._violations = active

    # --- the press and the parts ---------------------------------------------------------------------------------
    def _parts_under(self, lo: float, hi: float) -> Iterator[PartUnder]:
        """The parts on the machine whose extent along the belt overlaps [lo, hi]."""
        for p in self.parts.values():
            if p.state not in ("on", "held"):
                continue
            x, y, _ = p.pose()
            half = p.spec.length / 2
            if x + half > lo and x - half < hi:
                yield (p.id, x, half, y + p.spec.height / 2)

    def observables(self) -> dict[str, float]:
        """The belt's, and the tool tip height and speed of the press."""
        out = super().observables()
        out[f"{self.press.name}.z"] = self.press.z
        out[f"{self.press.name}.v"] = -self.press.axis.v
        return out

    def sample_observables(self) -> tuple[float, ...]:
        """The traced observables (``TRACED_OBSERVABLES``): the tool tip height."""
        return (self._z0 - self._axis.s,)

    # --- drawing -----------------------------------------------------------------------------------------------
    def bounds(self) -> tuple[float, float, float, float]:
        return (-40.0, -10.0, LENGTH + 50.0, 175.0)

    def static_drawables(self) -> list[Drawable]:
        px = self.press.x
        frame = [
            draw.polygon("press/column", draw.rect(LENGTH + 15.0, 0.0, LENGTH + 30.0, 160.0), draw.FRAME),
            draw.polygon("press/arm", draw.rect(px - 20.0, 145.0, LENGTH + 30.0, 160.0), draw.FRAME),
            draw.label("press/option", px + 30.0, 166.0, f"KS1 {self.ks1}"),
        ]
        return frame + super().static_drawables()
