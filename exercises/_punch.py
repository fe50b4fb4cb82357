"""What the punching-machine exercises 6.3.1–6.3.5 share: the model's tag table, the operator's cycles, and the
checks that compare the run with what the plant saw happen to each object (arrivals at OS2, press strokes)."""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from exercises._truth import GONE, Parts, parts_equal
from plcsim.check import (
    Check,
    Condition,
    Context,
    Verdict,
    all_of,
    always,
    any_of,
    event,
    event_data,
    final,
    never,
    off,
)
from plcsim.check.base import Names
from plcsim.exercise import IO, GradedCheck, only
from plcsim.scenario import after_event, held, place, remove, write
from plcsim.trace import Trace

PUNCH_IO = [
    IO("OS1", "light barrier at the loading place (belt start)", "Bool", "%I0.0", "NC"),
    IO("OS2", "light barrier under the press (belt end)", "Bool", "%I0.1", "NC"),
    IO(
        "KS1",
        "press upper limit switch",
        "Bool",
        "%I0.2",
        "NO",
        comment="upper, as all the textbook's solutions use it; the model text says lower (text issue 12)",
    ),
    IO("KS2", "press lower limit switch", "Bool", "%I0.3", "NO"),
    IO("M1_VPRED", "belt forward (towards the press)", "Bool", "%Q0.0"),
    IO("M1_VZAD", "belt backward (towards OS1)", "Bool", "%Q0.1"),
    IO("M2_DOLE", "press down", "Bool", "%Q0.2"),
    IO("M2_HORE", "press up", "Bool", "%Q0.3"),
]
"""Fig. 6.24, verbatim (all eight signals in every task: the model has them whether a task uses them or not)."""

MODEL = (
    "The model 'Punching Machine with Conveyor Belt 24V - Education': a conveyor belt driven by motor M1 forward "
    "(M1_VPRED, towards the press) and backward (M1_VZAD, towards the loading place), and at the end of the belt a "
    "punching device driven by motor M2 down (M2_DOLE) and up (M2_HORE). Two optical sensors on the belt, OS1 at "
    "the loading place and OS2 under the press, are wired as normally closed contacts: the input is TRUE while the "
    "beam is free and FALSE while an object interrupts it. The press's upper and lower positions are reported by "
    "the contact sensors KS1 (upper) and KS2 (lower), wired as normally open contacts (TRUE while actuated). The "
    "press waits at the top (KS1) when the model is switched on. In every task the machine is kept safe: no object "
    "falls off the belt or is damaged by the press, no motor is driven both ways at once, the press is never driven "
    "against an end stop, and the belt runs only while the press waits at the top (KS1), never while the press is "
    "driven."
)

BOTH_WAYS = "no motor is driven both ways at once"
BELT_WAITS = "the belt runs only while the press waits at the top (KS1), never while the press is driven"
"""The words of :data:`MODEL` the machine's safety checks grade (every task states them)."""

AUX = {
    "POM_P_OS1": ("%M1.0", "edge memory bit: rising edge of OS1 (object removed)"),
    "POM_N_OS2": ("%M1.1", "edge memory bit: falling edge of OS2 (object arrived)"),
    "POM_P_OS2": ("%M1.2", "edge memory bit: rising edge of OS2 (object left the press)"),
    "POM_P_KS2": ("%M1.3", "edge memory bit: rising edge of KS2 (the press is down)"),
}
"""The edge instructions' memory bits (the textbook does not name them)."""


def edge_bits(*names: str) -> list[IO]:
    """IO rows of the named edge memory bits."""
    return [IO(n, AUX[n][1], "Bool", AUX[n][0], comment="name and address proposed") for n in names]


def counts(*names: str) -> list[IO]:
    """IO rows of the Int parameters and counts (%MW10 on, two bytes each)."""
    glosses = {
        "M1_ZIADANY_POCET": "required number of moves to OS2 (an HMI parameter)",
        "M1_AKTUALNY_POCET": "moves to OS2 so far",
        "M2_ZIADANY_POCET": "required number of press strokes per visit (an HMI parameter)",
        "M2_AKTUALNY_POCET": "press strokes so far in this visit",
    }
    order = list(glosses)
    return [
        IO(
            n,
            glosses[n],
            "Int",
            f"%MW{10 + 2 * order.index(n)}",
            comment="address proposed" if "M1" in n else "name and address proposed (the textbook names neither)",
        )
        for n in names
    ]


# --------------------------------------------------------------------------------------------
# The operator
# --------------------------------------------------------------------------------------------

REST = ("1.5s", "2s", "1.7s", "2.2s")
"""How long each object rests at OS1 before the operator takes it (object by object: the operator is not a
metronome)."""


def cycles(
    objects: int, *, at: str = "OS1", writes: dict[int, dict[str, int]] | None = None, rest: tuple[str, ...] = REST
) -> list:
    """Objects p1..pN loaded one after the other at ``at``; each is taken away once it has rested in that
    station's beam for ``rest[k]``, the next loaded 1..2 s later. ``writes[k]`` are HMI writes made just before
    object k is loaded (object 1: at 0.1 s)."""
    writes = writes or {}
    actions: list = [write(tag, v, t="0.1s") for tag, v in writes.get(1, {}).items()]
    actions.append(place("p1", at=at, t="0.3s..0.8s"))
    for k in range(1, objects + 1):
        actions.append(remove(f"p{k}", when=held(at, rest[(k - 1) % len(rest)])))
        if k < objects:
            gone = after_event("part removed", f"p{k}")
            actions += [write(tag, v, when=gone, delay="0.3s..0.6s") for tag, v in writes.get(k + 1, {}).items()]
            actions.append(place(f"p{k + 1}", at=at, when=gone, delay="1s..2s"))
    return actions


TAKEN_FROM_THE_PRESS = "object taken from under the press"
STROKE_TO_UP = "0.3s..1.2s"
"""When, after a press stroke came down on it, the operator takes the object from under the press: while the ram
goes back up (the tip reaches KS2 0.12 s after the stroke, KS1 1.48 s after it). A removal while the ram is on its
way down is not a scenario: the stroke then comes down on an empty place, which the textbook's programs (they set
M2_DOLE and reset it only at KS2) cannot avoid and the text does not ask for."""


def taken_from_the_press(writes: dict[str, int]) -> list:
    """One object p1 loaded at OS1 after the HMI ``writes``; the operator takes it from under the press
    :data:`STROKE_TO_UP` after the first stroke came down on it, and loads nothing more."""
    return [
        *(write(tag, v, t="0.1s") for tag, v in writes.items()),
        place("p1", at="OS1", t="0.3s..0.8s"),
        remove("p1", when=after_event("press stroke"), delay=STROKE_TO_UP),
    ]


# --------------------------------------------------------------------------------------------
# What the plant saw: per object, per visit
# --------------------------------------------------------------------------------------------


def _placed(trace: Trace, ignore: tuple[str, ...]) -> dict[str, int]:
    return {
        e.part: e.t_ns
        for e in trace.events
        if e.source == "plant" and e.kind == "part placed" and e.part and e.part not in ignore
    }


def visits(trace: Trace, ignore: tuple[str, ...] = ()) -> list[tuple[str, int, int]]:
    """Every stay of an object in the OS2 beam: (part, from, to) in ns (to = the end of the run if it stays)."""
    out, since = [], {}
    end = int(trace.end_times[-1]) if len(trace) else 0
    for e in trace.events:
        if e.source != "plant" or not e.part or e.part in ignore:
            continue
        if e.kind == "part entered" and e.subject == "OS2":
            since[e.part] = e.t_ns
        elif e.part in since and ((e.kind == "part left" and e.subject == "OS2") or e.kind in GONE):
            out.append((e.part, since.pop(e.part), e.t_ns))
    out += [(p, t, end) for p, t in since.items()]
    return sorted(out, key=lambda v: v[1])


def strokes_of(trace: Trace) -> list[tuple[int, str | None]]:
    """Every press stroke: (time, the part under the press or None)."""
    return [(e.t_ns, e.part) for e in trace.events if e.source == "plant" and e.kind == "press stroke"]


@dataclass
class PerObject(Check):
    """For every object loaded, how often something happened to it equals what the parameters required.

    ``happened(trace, part, placed_ns)`` counts it, ``required(trace, placed_ns)`` is the number the task asks
    for; ``what`` words the count for the message ("arrived at OS2").
    """

    label: str
    what: str
    happened: Callable[[Trace, str, int], int]
    required: Callable[[Trace, int], int]
    reads: tuple[str, ...] = ()
    events: tuple[tuple[str, str | None], ...] = ()
    ignore: tuple[str, ...] = ()
    name: str | None = None
    weight: float = 1.0

    def names(self) -> Names:
        return Names(self.reads, (("part placed", None), *self.events)) + super().names()

    def describe(self) -> str:
        return self.label

    def evaluate(self, ctx: Context) -> Verdict:
        placed = _placed(ctx.trace, self.ignore)
        if not placed:
            return Verdict(False, f"expected {self.label}; no object was loaded", None, list(self.reads))
        for part, t in placed.items():
            n, want = self.happened(ctx.trace, part, t), self.required(ctx.trace, t)
            if n != want:
                params = ", ".join(f"{r} = {int(ctx.trace.value_at(r, t))}" for r in self.reads)
                why = f" ({params} when it was loaded at {ctx.t(t)})" if params else ""
                return Verdict(
                    False, f"object {part} {self.what} {n} time(s); expected {want}{why}", t, list(self.reads)
                )
        return Verdict(True, f"{len(placed)} object(s), each as required", None, list(self.reads))


@dataclass
class PerVisit(Check):
    """For every stay of an object under the press (in the OS2 beam), the number of press strokes on it equals
    ``required(trace, visit_start_ns)``."""

    label: str
    required: Callable[[Trace, int], int]
    reads: tuple[str, ...] = ()
    ignore: tuple[str, ...] = ()
    name: str | None = None
    weight: float = 1.0

    def names(self) -> Names:
        events = (("part entered", "OS2"), ("part left", "OS2"), ("press stroke", None))
        return Names(("OS2", "KS1", "KS2", *self.reads), events) + super().names()

    def describe(self) -> str:
        return self.label

    def evaluate(self, ctx: Context) -> Verdict:
        signals = ["OS2", "KS1", "KS2", "M2_DOLE", "M2_HORE", *self.reads]
        stays = visits(ctx.trace, self.ignore)
        if not stays:
            return Verdict(False, f"expected {self.label}; no object reached the press", None, signals)
        strokes = strokes_of(ctx.trace)
        for part, t0, t1 in stays:
            n = sum(1 for t, p in strokes if p == part and t0 <= t <= t1)
            want = self.required(ctx.trace, t0)
            if n != want:
                return Verdict(
                    False,
                    f"object {part} stayed under the press from {ctx.t(t0)} to {ctx.t(t1)} and was punched {n} "
                    f"time(s); expected {want}",
                    t0,
                    signals,
                    (t0, t1),
                )
        return Verdict(True, f"{len(stays)} stay(s) under the press, each punched as required", None, signals)


def arrivals(trace: Trace, part: str, _placed_ns: int) -> int:
    """How often the object entered the OS2 beam."""
    return sum(
        1
        for e in trace.events
        if e.source == "plant" and e.kind == "part entered" and e.subject == "OS2" and e.part == part
    )


def strokes_on(trace: Trace, part: str, _placed_ns: int) -> int:
    """How many press strokes came down on the object."""
    return sum(1 for _t, p in strokes_of(trace) if p == part)


def removed(trace: Trace, part: str, _placed_ns: int) -> int:
    """1 if the operator took the object away, 0 if it fell off or is still in the machine."""
    return int(any(e.source == "plant" and e.kind == "part removed" and e.part == part for e in trace.events))


def parameter(tag: str) -> Callable[[Trace, int], int]:
    """The value of a parameter tag when the object was loaded (or its stay under the press began)."""
    return lambda trace, t: int(trace.value_at(tag, t))


def product(first: str, second: str) -> Callable[[Trace, int], int]:
    """The product of two parameter tags when the object was loaded (strokes = moves × strokes per move)."""
    return lambda trace, t: int(trace.value_at(first, t)) * int(trace.value_at(second, t))


def constant(n: int) -> Callable[[Trace, int], int]:
    """The same number for every object (one stroke, one removal)."""
    return lambda _trace, _t: n


@dataclass(frozen=True)
class Arrivals:
    """Per scan: how often the object now in the machine has arrived at OS2 since it was loaded (0 once it has
    been taken away, and with no object). The count a program's M1_AKTUALNY_POCET must follow."""

    ignore: tuple[str, ...] = ()

    def counts(self, ctx: Context) -> np.ndarray:
        times = ctx.trace.times
        n = np.zeros(len(times), dtype=np.int64)
        for e in ctx.trace.events:
            if e.source != "plant" or not e.part or e.part in self.ignore:
                continue
            if e.kind == "part entered" and e.subject == "OS2":
                n += times >= e.t_ns
            elif e.kind in GONE:
                n[times >= e.t_ns] = 0
        return n

    def describe(self) -> str:
        return "arrivals of the object at OS2 since it was loaded"

    def signals(self) -> list[str]:
        return ["OS2", "OS1"]


@dataclass(frozen=True)
class AwaitingStroke(Condition):
    """True in the scans in which an object lies in the OS2 beam and no press stroke has come down on it since
    it got there: the object the press must start for."""

    def rows(self, ctx: Context) -> np.ndarray:
        times = ctx.trace.times
        out = np.zeros(len(times), dtype=bool)
        strokes = strokes_of(ctx.trace)
        for part, t0, t1 in visits(ctx.trace):
            first = min((t for t, p in strokes if p == part and t0 <= t <= t1), default=t1)
            out |= (times >= t0) & (times < first)
        return out

    def describe(self) -> str:
        return "an object under the press waits for its stroke"

    def signals(self) -> list[str]:
        return ["OS2"]

    def names(self) -> Names:
        return Names(("OS2",), (("part entered", "OS2"), ("part left", "OS2"), ("press stroke", None)))


@dataclass(frozen=True)
class Punched(Condition):
    """True in the scans in which an object lies in the OS2 beam and has had all the press strokes its stay
    requires (``required(trace, stay_start_ns)``): the object the belt must now carry back."""

    required: Callable[[Trace, int], int]
    label: str = "all its strokes"

    def rows(self, ctx: Context) -> np.ndarray:
        times = ctx.trace.times
        out = np.zeros(len(times), dtype=bool)
        strokes = strokes_of(ctx.trace)
        for part, t0, t1 in visits(ctx.trace):
            mine = [t for t, p in strokes if p == part and t0 <= t <= t1]
            n = self.required(ctx.trace, t0)
            if len(mine) >= n:
                done = mine[n - 1] if n > 0 else t0
                out |= (times >= done) & (times < t1)
        return out

    def describe(self) -> str:
        return f"the object under the press has had {self.label}"

    def signals(self) -> list[str]:
        return ["OS2"]

    def names(self) -> Names:
        return Names(("OS2",), (("part entered", "OS2"), ("part left", "OS2"), ("press stroke", None)))


COUNT_RUNG_MOVED = {
    "OB1: networks counting and removal swapped": (
        "OBJEKT_PRI_OS2, the program's own bit, follows the removal in the same scan instead of the next; the "
        "moves, the wait at OS1 and the count (6.3.2 criteria 1, 2) are the same"
    ),
    "OB1: network counting moved to the end": (
        "OBJEKT_PRI_OS2, the program's own bit, is read a scan after it changes, long before the object is "
        "back at OS1: the moves and the count (6.3.2 criteria 1, 2) are the same"
    ),
}
"""The mutants of 6.3.4's and 6.3.5's count rung that are correct programs by the spec's words (``spec_equivalent``)."""


# --------------------------------------------------------------------------------------------
# Checks every task shares
# --------------------------------------------------------------------------------------------


def interlocks(*, belt: bool = True, press: bool = True) -> list[Check]:
    """Criterion 2 of 6.3.1 and its counterpart for the press: no motor a task drives is driven both ways."""
    checks = []
    if belt:
        checks.append(
            never(all_of("M1_VPRED", "M1_VZAD"))
            .named("the belt is never driven forward and backward at once")
            .grades(BOTH_WAYS)
        )
    if press:
        checks.append(
            never(all_of("M2_DOLE", "M2_HORE")).named("the press is never driven down and up at once").grades(BOTH_WAYS)
        )
    return checks


def machine_safe() -> list[Check]:
    """What the plant says went wrong, whatever the task: nothing falls off, nothing is damaged, no stall, no
    interlock violation (both directions of a motor, belt and press moving together)."""
    return [
        never(event("part fell off")).named("no object falls off the belt").grades("no object falls off the belt"),
        never(event("part damaged")).named("no object is damaged by the press").grades("is damaged by the press"),
        never(event("axis stalled"))
        .named("the press is never driven against an end stop")
        .grades("the press is never driven against an end stop"),
        never(event("interlock violated")).named("the machine reports no interlock violation").grades(BELT_WAITS),
    ]


def shuttle(ignore: tuple[str, ...] = (), *, reverse_at_os2: bool = True) -> list[Check]:
    """Criterion 1 of 6.3.1, as states (each reaction within 1 scan: the scan that sees the object writes it):
    a loaded object starts the belt, OS2 stops it (and reverses it, unless the press must work first), the
    returning object stops at OS1. ``ignore``: objects the operator takes off the belt on purpose."""
    fresh = Parts("OS1", "OS2", ignore, "objects loaded that have not been at OS2 yet")
    checks = [
        never(all_of(off("OS1"), fresh > 0, off("M1_VPRED")))
        .named("an object loaded at OS1 starts the belt forward within 1 scan")
        .grades("the belt starts forward in the scan in which OS1 sees a loaded object"),
        never(all_of(off("OS2"), "M1_VPRED"))
        .named("the belt stops within 1 scan when the object reaches OS2")
        .grades("stops in the scan in which OS2 sees it"),
    ]
    if reverse_at_os2:
        checks.append(
            never(all_of(off("OS2"), off("M1_VZAD")))
            .named("the belt reverses within 1 scan at OS2")
            .grades("and reverses in that same scan")
        )
    checks.append(
        never(all_of(off("OS1"), "M1_VZAD"))
        .named("the returning object stops at OS1 within 1 scan")
        .grades("the returning object stops in the scan in which OS1 sees it")
    )
    return checks


def shuttle_words(*, reverse_at_os2: bool = True) -> str:
    """The task's sentence that :func:`shuttle` and :func:`waits_at_os1` grade (every shuttling task states it)."""
    reverse = ", and reverses in that same scan" if reverse_at_os2 else ""
    return (
        f"Each move starts and stops at once: the belt starts forward in the scan in which OS1 sees a loaded object "
        f"and stops in the scan in which OS2 sees it{reverse}; the returning object stops in the scan in which OS1 "
        f"sees it and {WAITS}."
    )


WAITS = "waits there until the operator takes it away"
COUNTED = "0 again once the object has been removed"
"""The words of the tasks that :func:`waits_at_os1` and :func:`counts_arrivals` grade."""
PRESS_JAM = (
    "The press may jam on its way down (a fault of the machine) and be freed a few seconds later; it then goes on down "
    "to KS2 and the stroke is finished as usual, the machine kept safe meanwhile."
)
"""6.3.3-6.3.5's fault scenario 'jammed press', as their tasks state it (``Scenario(outside={FAULTS: ...})``)."""
PRESS_WORDS = (
    "The press goes down only for an object at OS2; if the operator takes the object from under the press, the press "
    "strikes no more and waits at the top (KS1)."
)
"""6.3.4's and 6.3.5's sentence on the press, which :func:`taken_checks` grades."""
TAKEN_ON_ITS_WAY = (
    "If the operator takes an object off the belt on its way to OS2 (no sensor sees that), the next object loaded at "
    "OS1 is served as usual."
)
"""6.3.1's and 6.3.2's fault scenario 'object taken on its way', as their tasks state it."""


def waits_at_os1(ignore: tuple[str, ...] = ()) -> Check:
    """Criterion of the shuttling tasks: each object, back at OS1, stays until the operator takes it away."""
    return PerObject(
        "every object waits at OS1 until it is taken away",
        "was taken away at OS1",
        removed,
        constant(1),
        events=(("part removed", None),),
        ignore=ignore,
    ).grades(WAITS)


def counts_arrivals(ignore: tuple[str, ...] = ()) -> Check:
    """6.3.2 criterion 2 (kept by 6.3.4 and 6.3.5): M1_AKTUALNY_POCET follows the object's arrivals at OS2
    (``ignore``: objects taken off the belt before they arrived, whose removal no sensor sees)."""
    return (
        always(parts_equal("M1_AKTUALNY_POCET", Arrivals(ignore)))
        .named("M1_AKTUALNY_POCET counts the object's arrivals at OS2 and is 0 after its removal")
        .grades(COUNTED)
    )


def strokes_land_on_objects() -> Check:
    """The plant's account of each stroke: it came down on an object, near the object's centre (a stroke on an
    empty place has no offset and fails)."""
    return event_data("press stroke", "offset_mm").between(-15, 15).named("every stroke comes down on an object")


def belt_waits_for_the_press() -> list[Check]:
    """6.3.4 criterion 2 on the PLC's outputs: the belt never moves while the press is away from KS1 or driven (the
    machine's own word on it is :func:`machine_safe`'s interlock check)."""
    return [
        never(all_of(any_of("M1_VPRED", "M1_VZAD"), any_of(off("KS1"), "M2_DOLE", "M2_HORE")))
        .named("the belt never runs while the press is away from KS1 or moving")
        .grades(BELT_WAITS),
    ]


def taken_checks() -> list[Check | GradedCheck]:
    """What a program must do when the object is taken from under the press between two strokes (or after its
    stroke): no stroke without an object (6.3.3 criterion 2, kept by 6.3.4) and the ram back at KS1. Not what the
    belt does then: the task does not say (the textbook's programs stand, a step sequencer waiting for the object's
    return may run the belt back to OS1), so a check of it would fail correct programs."""
    return [
        never(all_of("OS2", "M2_DOLE"))
        .named("the press goes down only for an object at OS2")
        .grades("The press goes down only for an object at OS2"),
        only(
            final("KS1")
            .equals(1)
            .named("the press finishes its stroke and waits at KS1")
            .grades("the press strikes no more and waits at the top (KS1)"),
            TAKEN_FROM_THE_PRESS,
        ),
    ]


def punching_checks(
    strokes_per_visit: Callable[[Trace, int], int],
    per_object: Callable[[Trace, int], int],
    label: str,
    reads: tuple[str, ...],
    whole: tuple[str, ...],
) -> list[Check | GradedCheck]:
    """The checks 6.3.4 and 6.3.5 share: strokes per stay and per object, the reverse after the last stroke,
    the moves, the belt waiting for the press, the shuttle of 6.3.1, the interlocks and :func:`taken_checks`.
    ``whole``: the scenarios in which every object makes its whole cycle (the strokes, moves and count checks are
    graded there, not on an object taken from under the press)."""
    return [
        # criterion 1
        only(
            PerVisit(
                f"every stay under the press gets {label}",
                strokes_per_visit,
                reads=tuple(r for r in reads if "M2" in r),
            ),
            *whole,
        ),
        strokes_land_on_objects(),
        only(
            PerObject(
                f"every object is punched {' × '.join(reads)} times",
                "was punched",
                strokes_on,
                per_object,
                reads=reads,
                events=(("press stroke", None),),
            ),
            *whole,
        ),
        only(
            PerObject(
                "every object is carried to OS2 M1_ZIADANY_POCET times",
                "arrived at OS2",
                arrivals,
                parameter("M1_ZIADANY_POCET"),
                reads=("M1_ZIADANY_POCET",),
                events=(("part entered", "OS2"),),
            ),
            *whole,
        ),
        only(counts_arrivals(), *whole),
        # criterion 2
        *belt_waits_for_the_press(),
        # criterion 3
        never(all_of(Punched(strokes_per_visit, label), "KS1", off("M1_VZAD"))).named(
            "the belt reverses within 1 scan once the press is back at KS1 after the last stroke"
        ),
        # criterion 4
        waits_at_os1(),
        *shuttle(reverse_at_os2=False),
        *interlocks(),
        *machine_safe(),
        *taken_checks(),
    ]
