"""4.3.6 Conveyor control 2 (any number of objects). Plant: CONV1.

Also home of two small conditions the checker language lacks (used by 4.3.9 and 4.3.10 too):
:class:`Parts` (how many parts the plant's own events put in a stretch of the line: the truth a
program's count or occupancy bit must follow) and :class:`EdgeBalance` (rising edges of one input
minus those of another, as the PLC saw them).
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass

import numpy as np

from exercises._common import SOLUTIONS, solution
from plants import Conv1
from plcsim.check import Condition, Context, all_of, always, count, event, falls, final, implies, never, off, rises
from plcsim.exercise import IO, Exercise, Solution, only
from plcsim.scenario import Scenario, after_event, chatter, held, place, remove

NUMBER = "4.3.6"

GONE = ("part removed", "part fell off", "part knocked off")


# --------------------------------------------------------------------------------------------
# Plant truth as conditions
# --------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class Parts:
    """The number of parts in a stretch of the line, per scan, from the plant's events.

    A part is in the stretch from its first ``part entered <start>`` until its first
    ``part entered <end>`` (``end=None``: until it leaves the plant: removed, fallen or knocked off).
    Parts named in ``ignore`` (an operator's hand modelled as a block) are not counted. Events are
    stamped with the time the PLC's next scan reads them, so the count changes in the very scan
    whose input image shows the beam change.
    """

    start: str
    end: str | None = None
    ignore: tuple[str, ...] = ()
    label: str = ""

    def counts(self, ctx: Context) -> np.ndarray:
        entered: dict[str, int] = {}
        left: dict[str, int] = {}
        for e in ctx.trace.events:
            if e.source != "plant" or not e.part or e.part in self.ignore:
                continue
            if e.kind == "part entered" and e.subject == self.start:
                entered.setdefault(e.part, e.t_ns)
            elif e.part in entered and e.part not in left and (
                (e.kind == "part entered" and e.subject == self.end) or e.kind in GONE
            ):
                left[e.part] = e.t_ns
        times = ctx.trace.times
        n = np.zeros(len(times), dtype=np.int64)
        for part, t_in in entered.items():
            n += times >= t_in
            if part in left:
                n -= times >= left[part]
        return n

    def describe(self) -> str:
        if self.label:
            return self.label
        where = f"between {self.start} and {self.end}" if self.end else f"past {self.start}"
        return f"parts {where}"

    # conditions
    def __gt__(self, k: int) -> Condition:  # type: ignore[override]
        return _PartsCompare(self, ">", k)

    def __eq__(self, k: object) -> Condition:  # type: ignore[override]
        return _PartsCompare(self, "==", k)

    def __le__(self, k: int) -> Condition:  # type: ignore[override]
        return _PartsCompare(self, "<=", k)

    def __hash__(self) -> int:
        return hash((self.start, self.end, self.ignore))


@dataclass(frozen=True)
class _PartsCompare(Condition):
    parts: Parts
    op: str
    k: int

    def rows(self, ctx: Context) -> np.ndarray:
        n = self.parts.counts(ctx)
        return {">": n > self.k, "==": n == self.k, "<=": n <= self.k}[self.op]

    def describe(self) -> str:
        return f"({self.parts.describe()}) {self.op} {self.k}"


@dataclass(frozen=True)
class CountIs(Condition):
    """A numeric tag equals a count computed from the run (:class:`Parts` or :class:`EdgeBalance`)."""

    name: str
    truth: Parts | EdgeBalance

    def rows(self, ctx: Context) -> np.ndarray:
        return ctx.trace.column(self.name).astype(np.int64) == self.truth.counts(ctx)

    def describe(self) -> str:
        return f"{self.name} == {self.truth.describe()}"

    def signals(self) -> list[str]:
        return [self.name, *self.truth.signals()] if isinstance(self.truth, EdgeBalance) else [self.name]


@dataclass(frozen=True)
class FlagIs(Condition):
    """A Bool tag is TRUE exactly while the stretch holds at least one part."""

    name: str
    truth: Parts

    def rows(self, ctx: Context) -> np.ndarray:
        return ctx.trace.column(self.name).astype(bool) == (self.truth.counts(ctx) > 0)

    def describe(self) -> str:
        return f"{self.name} == ({self.truth.describe()} > 0)"

    def signals(self) -> list[str]:
        return [self.name]


@dataclass(frozen=True)
class EdgeBalance:
    """Per scan: rising edges of ``up`` minus rising edges of ``down`` so far, as the PLC's input image saw them."""

    up: str
    down: str

    def counts(self, ctx: Context) -> np.ndarray:
        out = np.zeros(len(ctx.trace), dtype=np.int64)
        for name, sign in ((self.up, 1), (self.down, -1)):
            col = ctx.trace.column(name).astype(bool)
            rise = col & ~np.concatenate(([False], col[:-1]))
            out += sign * np.cumsum(rise)
        return out

    def describe(self) -> str:
        return f"(rising edges of {self.up}) - (rising edges of {self.down})"

    def signals(self) -> list[str]:
        return [self.up, self.down]


def parts_equal(name: str, truth: Parts | EdgeBalance) -> Condition:
    """``name`` equals the count in every scan."""
    return CountIs(name, truth)


def flag_matches(name: str, truth: Parts) -> Condition:
    """``name`` is TRUE exactly while a part is in the stretch."""
    return FlagIs(name, truth)


# --------------------------------------------------------------------------------------------
# The exercise
# --------------------------------------------------------------------------------------------

ON_BELT = Parts("S1", "S2", label="objects that passed S1 but have not reached S2")
HOLDS = ("1s", "1.4s", "0.8s", "1.2s", "1s")  # how long the operator lets each object wait at S2


def removals(holds: Iterable[str]) -> list:
    """The operator takes the object at S2 away once it has waited there (one action per object)."""
    return [remove("S2", when=held("S2", h)) for h in holds]


def five_objects() -> list:
    """Three objects loaded in a row; a fourth while the belt waits with the first at S2; a fifth later."""
    return [
        place("p1", at="S1", t="0.3s..0.8s"),
        place("p2", at="S1", when=after_event("part left", "p1"), delay="0.8s..1.5s"),
        place("p3", at="S1", when=after_event("part left", "p2"), delay="0.8s..1.5s"),
        place("p4", at="S1", when=held("S2", "0.2s"), delay="0s..0.5s"),
        place("p5", at="S1", when=after_event("part removed", "p3"), delay="0.3s..1s"),
        *removals(HOLDS),
    ]


EXERCISE = Exercise(
    number=NUMBER,
    slug="conveyor-2",
    title="Conveyor control 2 (any number of objects)",
    title_sk="Príklad 6 – Ovládanie dopravníka 2",
    task=(
        "The conveyor of 4.3.5: sensor S1 at the beginning and S2 at the end, both wired as normally open "
        "contacts; output D1 (conveyor forward) drives the belt from S1 to S2.\n"
        "Task: objects loaded at the beginning (and detected by S1) are carried to the end of the conveyor; S2 "
        "switches the conveyor off. Any number of objects may be on the conveyor. S2 may stop the belt while "
        "another object is still in the middle, so after the object at the end has been removed the program must "
        "know whether objects are left between S1 and S2: count them. Keep the count in POCET (number of "
        "objects, Int), either as an up/down counter CTUD whose CV output is wired to POCET, or with ADD/SUB on "
        "the edges of S1 and S2."
    ),
    io=[
        IO("S1", "sensor at the belt start", "Bool", "%I0.0", "NO", comment="address proposed"),
        IO("S2", "sensor at the belt end", "Bool", "%I0.1", "NO", comment="address proposed"),
        IO("D1", "conveyor forward", "Bool", "%Q0.2", comment="address stated in 4.3.14"),
        IO("POCET", "number of objects between S1 and S2", "Int", None,
           comment="symbolic tag; textbook solution 2 (solution 1: the CTUD's CV)"),
    ],
    rig=Conv1,
    scenarios=[
        Scenario("five objects", *five_objects(), duration="34s",
                 description="three objects loaded in a row; the first stops the belt at S2 with two in the middle; "
                 "a fourth is loaded while the belt waits, a fifth after the third removal; each is taken from S2 "
                 "after waiting 0.8..1.4 s"),
        Scenario("noisy S1", chatter("S1", t="0s"),
                 place("p1", at="S1", t="0.3s..0.8s"),
                 place("p2", at="S1", when=after_event("part left", "p1"), delay="1s..2s"),
                 *removals(("1s", "1s")), duration="16s",
                 description="demonstration (textbook, not pass/fail): S1 bounces 3..5 times at every beam change, "
                 "so each object is counted several times; the count never returns to 0 and the belt runs on "
                 "after the last removal"),
        Scenario("noisy S2", chatter("S2", when=held("S2", "0.5s")),
                 place("p1", at="S1", t="0.3s..0.8s"),
                 place("p2", at="S1", when=after_event("part removed", "S2"), delay="1s..2s"),
                 *removals(("1s",)), duration="12s",
                 description="demonstration (textbook, not pass/fail): S2 bounces while the operator takes the "
                 "object away, the count drops below 0 and a newly loaded object does not start the belt"),
    ],
    checks=[
        only(count(event("part entered", "S2")).equals(5).named("every loaded object arrives at S2"),
             "five objects"),
        only(always(implies("S2", off("D1"))).named("the belt never runs while S2 sees an object"), "five objects"),
        only(rises("D1").within("1 scan").after(rises("S1"), provided=all_of(off("S2"), ON_BELT == 1))
             .named("an object loaded on the empty belt starts it"), "five objects"),
        only(rises("D1").within("1 scan").after(falls("S2"), provided=ON_BELT > 0)
             .named("after a removal the belt restarts while objects remain"), "five objects"),
        only(never(all_of("D1", ON_BELT == 0)).named("the belt never runs with no object between S1 and S2"),
             "five objects"),
        only(always(parts_equal("POCET", ON_BELT)).named("POCET equals the number of objects between S1 and S2"),
             "five objects"),
        only(final("POCET").equals(0).named("POCET is 0 when the belt is empty"), "five objects"),
        only(always(parts_equal("POCET", EdgeBalance("S1", "S2")))
             .named("POCET counts the S1 edges up and the S2 edges down"), "noisy S1", "noisy S2"),
        never(event("part fell off")).named("no object falls off the belt"),
    ],
    solutions=[
        solution(NUMBER, "reference", explanation="CTUD: CU := S1, CD := S2, CV => POCET; D1 := NOT S2 AND CV > 0"),
        solution(NUMBER, "solution-2", "alternative",
                 "ADD/SUB of POCET on the rising edges of S1 and S2; D1 := NOT S2 AND POCET > 0"),
        solution(NUMBER, "wrong-no-edges", "wrong",
                 "ADD/SUB without edges run in every scan a sensor is covered: POCET is not the number of objects",
                 fails=("POCET equals the number of objects between S1 and S2",)),
        Solution("wrong-single-object", SOLUTIONS / "4_3_06" / "wrong-single-object.py", "wrong",
                 "the one-object program of 4.3.5: after the first object is removed nothing knows that others "
                 "wait in the middle, so the belt stays off",
                 ("every loaded object arrives at S2", "after a removal the belt restarts while objects remain")),
    ],
    notes=(
        "Criterion 5 (noisy sensors) is a demonstration in the textbook, not pass/fail. It ships as the scenarios "
        "'noisy S1' and 'noisy S2', graded only on what stays true with noise (POCET follows the edges the PLC "
        "saw; nothing falls off); the count drifting away from the true number of objects is the thing to look "
        "at in the POCET plot. 'In loading order' (criterion 1) needs no check: parts on one belt cannot overtake. "
        "POCET is required by name so that both textbook solutions can be graded on their count (the CTUD "
        "solution wires its CV output to POCET)."
    ),
)
