"""4.3.10 Conveyors 2 (two conveyors, two NC sensors each). Plant: CONV2x2.

Mutation testing (``plcsim mutate 4.3.10``): three mutants survive, and each starts D1 one scan later than
the reference; ``spec_equivalent`` says why they are correct programs. The equivalent ones are swaps of
adjacent networks that never act in the same scan.
"""

from __future__ import annotations

from exercises._common import solution
from exercises._truth import Parts, flag_matches
from plants import Conv2x2
from plcsim.check import (
    action,
    all_of,
    always,
    any_of,
    assumes,
    count,
    event,
    falls,
    implies,
    never,
    off,
    program_uses_no,
)
from plcsim.exercise import IO, Exercise, only
from plcsim.scenario import FAULTS, Scenario, after_event, held, place, remove, wire_break
from plcsim.tags import DB
from plcsim.tags.types import Bool

NUMBER = "4.3.10"
FAULT_WORDS = "A broken sensor wire reads FALSE, 'object present': at D2_OS2 it stops D2 at once"
"""The task's words for its fault scenarios (``Scenario(outside=...)``)."""
PER_CONVEYOR = "Consider one object per conveyor"
"""The operating condition the task states (the textbook: 'always only one object on one conveyor')."""
POSITIONS = (
    "An object occupies position 1 of a conveyor from the scan in which the conveyor's start sensor sees it until "
    "the scan in which its end sensor sees it, and position 2 from then until D2_OS1 sees it (on D1) or it is "
    "removed (on D2)"
)
"""The task's definition of the positions, which the occupancy states are graded against scan by scan."""

STRAY = ("stray",)  # a part put straight in front of D1_OS2 on the idle model: by design not an object of the line
D1_POZ1 = Parts("D1_OS1", "D1_OS2", STRAY, "objects at D1 position 1")
D1_POZ2 = Parts("D1_OS2", "D2_OS1", STRAY, "objects at D1 position 2")
D2_POZ1 = Parts("D2_OS1", "D2_OS2", STRAY, "objects at D2 position 1")
D2_POZ2 = Parts("D2_OS2", None, STRAY, "objects at D2 position 2")
ON_D1 = Parts("D1_OS1", "D2_OS1", STRAY, "objects on D1")
ON_D2 = Parts("D2_OS1", None, STRAY, "objects on D2")
TRUTH_SCENARIOS = ("two objects", "placed at D1_OS2")

# present(X) = NOT X for the NC barriers
D2_FULL = any_of("DATA.D2_POZ1_OBS", "DATA.D2_POZ2_OBS")

EXERCISE = Exercise(
    number=NUMBER,
    slug="conveyors-2",
    title="Conveyors 2 (two conveyors, two NC sensors each)",
    title_sk="Príklad 10 – Ovládanie dopravníkov 2",
    task=(
        "Two conveyors D1 and D2 in series are driven forward by D1_VPRED and D2_VPRED (conveyor n forward). Each "
        "has two optical sensors: D1_OS1 at the start and D1_OS2 at the end of D1, D2_OS1 at the start and D2_OS2 at "
        "the end of D2. All four are wired as normally closed contacts: the input is TRUE while the beam is free and "
        "FALSE while an object interrupts it.\n"
        "Task: create occupancy states in the global data block DATA (D1_POZ1_OBS, D1_POZ2_OBS, D2_POZ1_OBS, "
        "D2_POZ2_OBS: position 1 or 2 of conveyor n occupied) that indicate an object even where no sensor sees "
        "it, and with them carry objects from the start of D1 to the end of D2, onto D2 only if D2 is free. "
        + POSITIONS
        + ". An object loaded on D1 and seen by D1_OS1 is carried to the end of D1 if that position is free; from "
        "D1_OS2 it goes on to D2; when D2_OS1 sees it, D1 stops and the object continues to the end of D2, where it "
        "stops and waits for removal by hand, which clears the occupancy. "
        + PER_CONVEYOR
        + ". Do not use edge instructions. Each conveyor stops in the scan in which its stop sensor sees the object, "
        "and the removal at D2_OS2 clears D2_POZ2_OBS in the scan that sees it. An object put straight in front of "
        "D1_OS2 on the idle model (not loaded at D1_OS1) is not registered and starts nothing. A broken sensor wire "
        "reads FALSE, 'object present': at D2_OS2 it stops D2 at once. No object falls off, and D2 never runs while "
        "its end position is occupied."
    ),
    io=[
        IO("D1_OS1", "D1 start sensor", "Bool", "%I0.0", "NC"),
        IO("D1_OS2", "D1 end sensor", "Bool", "%I0.1", "NC"),
        IO("D2_OS1", "D2 start sensor", "Bool", "%I0.2", "NC"),
        IO("D2_OS2", "D2 end sensor", "Bool", "%I0.3", "NC"),
        IO("D1_VPRED", "conveyor 1 forward", "Bool", "%Q0.0"),
        IO("D2_VPRED", "conveyor 2 forward", "Bool", "%Q0.1"),
    ],
    dbs={
        "DATA": DB(
            D1_POZ1_OBS=Bool(False),
            D1_POZ2_OBS=Bool(False),
            D2_POZ1_OBS=Bool(False),
            D2_POZ2_OBS=Bool(False),
            comment="occupancy of the four positions (Fig. 4.95)",
        )
    },
    rig=Conv2x2,
    scenarios=[
        Scenario(
            "two objects",
            place("p1", at="D1_OS1", t="0.3s..0.8s"),
            place("p2", at="D1_OS1", when=after_event("part entered", "D2_OS1"), delay="0.3s..1s"),
            remove("D2_OS2", when=held("D2_OS2", "3s")),
            remove("D2_OS2", when=held("D2_OS2", "3.5s")),
            duration="25s",
            description="p1 is carried to D2_OS2 and waits; p2, loaded once p1 is on D2, waits at D1_OS2; p1 "
            "is taken away 3 s after its arrival and p2 is delivered, then taken away too",
        ),
        Scenario(
            "placed at D1_OS2",
            place("stray", at="D1_OS2", t="0.3s..0.8s"),
            remove("stray", t="2s..2.5s"),
            duration="3s",
            description="an object put straight in front of D1_OS2 on the idle model, and taken away again",
        ),
        Scenario(
            "wire break",
            place("p1", at="D1_OS1", t="0.3s..0.8s"),
            wire_break("D2_OS2", when=after_event("part entered", "D2_OS1"), delay="1s..3s"),
            outside={FAULTS: FAULT_WORDS},
            duration="12s",
            description="the wire of D2_OS2 breaks while p1 travels on D2: the NC input reads FALSE, 'object present'",
        ),
    ],
    checks=[
        # criterion 1
        only(count(event("part entered", "D2_OS2")).equals(2).named("both objects end at D2_OS2"), "two objects"),
        only(
            falls("D1_VPRED")
            .within("1 scan")
            .after(falls("D2_OS1"), provided=ON_D2 > 0)
            .named("D1 stops within 1 scan when D2_OS1 sees the object"),
            "two objects",
            "wire break",
        ),
        only(
            falls("D2_VPRED")
            .within("1 scan")
            .after(falls("D2_OS2"))
            .named("D2 stops within 1 scan when D2_OS2 sees the object"),
            "two objects",
        ),
        # criterion 2
        never(all_of("D1_VPRED", "DATA.D1_POZ2_OBS", D2_FULL)).named("D1 never sends an object to an occupied D2"),
        only(always(ON_D2 <= 1).named("never more than one object on D2"), "two objects"),
        # criterion 3
        only(
            never(any_of("D1_VPRED", "D2_VPRED", "DATA.D1_POZ2_OBS")).named(
                "an object put at D1_OS2 on the idle model is not registered and starts nothing"
            ),
            "placed at D1_OS2",
        ),
        # criterion 4
        only(
            falls("DATA.D2_POZ2_OBS")
            .within("1 scan")
            .after(event("part removed", "D2_OS2"))
            .named("removing the object at D2_OS2 clears D2_POZ2_OBS within 1 scan"),
            "two objects",
        ),
        # criterion 5
        only(
            always(flag_matches("DATA.D1_POZ1_OBS", D1_POZ1)).named("D1_POZ1_OBS matches the object at D1 position 1"),
            *TRUTH_SCENARIOS,
        ),
        only(
            always(flag_matches("DATA.D1_POZ2_OBS", D1_POZ2)).named("D1_POZ2_OBS matches the object at D1 position 2"),
            *TRUTH_SCENARIOS,
        ),
        only(
            always(flag_matches("DATA.D2_POZ1_OBS", D2_POZ1)).named("D2_POZ1_OBS matches the object at D2 position 1"),
            *TRUTH_SCENARIOS,
        ),
        only(
            always(flag_matches("DATA.D2_POZ2_OBS", D2_POZ2)).named("D2_POZ2_OBS matches the object at D2 position 2"),
            *TRUTH_SCENARIOS,
        ),
        # the NC wiring's point
        only(
            falls("D2_VPRED")
            .within("1 scan")
            .after(action("break_wire", "D2_OS2"))
            .named("a broken D2_OS2 wire stops D2 at once (it reads 'object present')"),
            "wire break",
        ),
        never(event("part fell off")).named("no object falls off"),
        always(implies("D2_VPRED", off("DATA.D2_POZ2_OBS"))).named("D2 never runs with its end position occupied"),
        # criterion 6
        program_uses_no("EDGE").named("no edge instructions").points(0.5),
    ],
    conditions=[assumes(PER_CONVEYOR, always(all_of(ON_D1 <= 1, ON_D2 <= 1)))],
    requirements={
        "both objects end at D2_OS2": "carry objects from the start of D1 to the end of D2",
        "D1 stops within 1 scan when D2_OS1 sees the object": (
            "Each conveyor stops in the scan in which its stop sensor sees the object"
        ),
        "D2 stops within 1 scan when D2_OS2 sees the object": (
            "Each conveyor stops in the scan in which its stop sensor sees the object"
        ),
        "D1 never sends an object to an occupied D2": "onto D2 only if D2 is free",
        "never more than one object on D2": "onto D2 only if D2 is free",
        "an object put at D1_OS2 on the idle model is not registered and starts nothing": (
            "is not registered and starts nothing"
        ),
        "removing the object at D2_OS2 clears D2_POZ2_OBS within 1 scan": (
            "the removal at D2_OS2 clears D2_POZ2_OBS in the scan that sees it"
        ),
        "D1_POZ1_OBS matches the object at D1 position 1": POSITIONS,
        "D1_POZ2_OBS matches the object at D1 position 2": POSITIONS,
        "D2_POZ1_OBS matches the object at D2 position 1": POSITIONS,
        "D2_POZ2_OBS matches the object at D2 position 2": POSITIONS,
        "a broken D2_OS2 wire stops D2 at once (it reads 'object present')": "at D2_OS2 it stops D2 at once",
        "no object falls off": "No object falls off",
        "D2 never runs with its end position occupied": "D2 never runs while its end position is occupied",
        "no edge instructions": "Do not use edge instructions",
    },
    solutions=[
        solution(
            NUMBER,
            "reference",
            explanation="four occupancy states in DB DATA, set by the NC sensors while the "
            "conveyor runs and the position is free; no edges",
        ),
        solution(
            NUMBER,
            "simplified-d2",
            "alternative",
            "D2_VPRED := (D1_POZ2_OBS OR D2_POZ1_OBS) AND NOT D2_POZ2_OBS (Fig. 4.103)",
        ),
        solution(
            NUMBER,
            "wrong-send-to-full-d2",
            "wrong",
            "D1 sends to D2 although D2's end position is occupied",
            fails=("D1 never sends an object to an occupied D2",),
        ),
        solution(
            NUMBER,
            "wrong-no-running-condition",
            "wrong",
            "without the D1_VPRED contact an object put at D1_OS2 on the idle model is registered and carried",
            fails=("an object put at D1_OS2 on the idle model is not registered and starts nothing",),
        ),
        solution(
            NUMBER,
            "wrong-nc-as-no",
            "wrong",
            "(not from the textbook) NC inputs read as NO: every free beam looks like an object",
            fails=("D1_POZ1_OBS matches the object at D1 position 1",),
        ),
    ],
    spec_equivalent={
        "OB1: network loading moved to the end": (
            "D1_VPRED sees the new D1_POZ1_OBS a scan later, so D1 starts one scan later: the spec bounds when a "
            "conveyor stops and when the removal clears D2_POZ2_OBS (criteria 1 and 4, 'within 1 scan'), not when "
            "it starts"
        ),
        "OB1: network removal moved to the end": (
            "the removal still clears D2_POZ2_OBS in the scan that saw it (criterion 4), and the waiting object "
            "is sent on a scan later: the spec does not bound when a conveyor starts"
        ),
        "OB1: networks removal and run_d1 swapped": (
            "after the removal at D2_OS2 the waiting object is sent on a scan later; D2_POZ2_OBS is still cleared "
            "in the scan that saw the removal (criterion 4): the spec does not bound when a conveyor starts"
        ),
    },
    notes=(
        "The DB DATA is the exercise's (Fig. 4.95, non-retentive, start values FALSE). The wire-break scenario is the "
        "NC wiring's point (a broken wire reads 'object present', so the end sensor stops the belt instead of "
        "letting the object run off); the occupancy is then wrong by construction, so the truth checks are not "
        "applied there. The true positions come from the plant's events in the textbook's sense (an object is at "
        "position 1 of D1 from D1_OS1 until D1_OS2 sees it, and so on); the part put straight at D1_OS2 is not an "
        "object of the line (the textbook: it is not registered). Rung 6 is taken with the D2_POZ1_OBS test (the "
        "text: with one object per conveyor both forms behave the same). Criterion 6 is a static check worth half a "
        "point."
    ),
)
