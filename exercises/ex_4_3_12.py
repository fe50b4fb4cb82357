"""4.3.12 Piston control (object aligner). Plant: ALIGN (top view, ``plants/align.py``).

The alignment is the plant's own measurement: when the plate is back after a full stroke (and when the object is
taken away) ALIGN reports ``alignment measured`` with the gap of the object's fence-side edge and its turn, and the
checks grade those numbers against the task's tolerance (≤ 1 mm, ≤ 2°), so a program that strokes too short or not
at all cannot pass by its bits alone.
"""

from __future__ import annotations

from exercises._common import solution
from plants.align import JAM_PISTON, Align
from plcsim.check import all_of, count, event, event_data, final, holds, never, off, on, rises
from plcsim.exercise import IO, Exercise, only
from plcsim.scenario import FAULTS, Scenario, after_event, place, remove, wire_break

NUMBER = "4.3.12"
FAULT_WORDS = "it never comes when the piston jams or the rear sensor is dead"
"""The task's words for its fault scenarios (``Scenario(outside=...)``)."""
CROOKED = {"offset_mm": (0.0, 15.0), "angle_deg": (-15.0, 15.0)}  # §5.5: 0–15 mm off the fence, ±15°
ROBOT = "0.5s..1s"  # the robot takes the aligned object this long after the plate is back

TWO = "two objects"
STAYS = "object stays"
BRIEF = "object passes"
JAMMED = "piston jammed"
DEAD = "rear sensor dead"

EXERCISE = Exercise(
    number=NUMBER,
    slug="piston-aligner",
    title="Piston control (object aligner)",
    title_sk="Príklad 12 – Ovládanie piestu",
    task=(
        "An object arriving on a conveyor is detected by an optical sensor OS. Before a robot takes it, it must be "
        "aligned so that the robot does not collide with it. One output drives the piston forward "
        "(PIEST_CHOD_VPRED; FALSE = the piston returns); its end positions are detected by the sensors "
        "PIEST_SNIMAC_VPRED (front) and PIEST_SNIMAC_VZAD (rear).\n"
        "Task: when the object is detected by the optical sensor, align it after 1 s by moving the piston forward "
        "and back. Use the memory bits ZAROVNAJ (alignment in progress), OBJ_ZAROVNANY (object aligned) and "
        "BOL_VPRED (the piston was forward: blocks a repeated forward stroke), or a step variable KROK. The piston "
        "starts forward 1 s after the object is detected (at most 2 scans later) and makes one full stroke per "
        "object, forward to the front sensor and back to the rear, and none more while the object stays; its "
        "output is off once the stroke is done. An object seen for less than 1 s gets no stroke. Each object ends "
        "against the fence (within 1 mm) and square (within 2°). OBJ_ZAROVNANY tells the robot it may take the "
        "object: it comes only once the piston is back at the rear sensor and stays while the aligned object is "
        "there, so it never comes when the piston jams or the rear sensor is dead; the next object is aligned again."
    ),
    io=[
        IO("OS", "optical object sensor", "Bool", "%I0.0", "NO", comment="address and wiring proposed (§5.5)"),
        IO("PIEST_SNIMAC_VPRED", "piston front end-position sensor", "Bool", "%I0.1", "NO", comment="proposed"),
        IO("PIEST_SNIMAC_VZAD", "piston rear end-position sensor", "Bool", "%I0.2", "NO", comment="proposed"),
        IO("PIEST_CHOD_VPRED", "piston forward (FALSE = return)", "Bool", "%Q0.0", comment="address proposed"),
        IO("ZAROVNAJ", "align: TRUE during the alignment", "Bool", "%M0.0", comment="address proposed"),
        IO("OBJ_ZAROVNANY", "object aligned", "Bool", "%M0.1", comment="address proposed"),
        IO("BOL_VPRED", "was forward: blocks a repeated forward stroke", "Bool", "%M0.2", comment="proposed"),
        IO("VZAD_HRANA", "edge memory of P(PIEST_SNIMAC_VZAD)", "Bool", "%M0.3", comment="proposed"),
        IO("KROK", "step number (solution 2)", "Int", "%MW2", comment="address proposed"),
    ],
    rig=Align,
    scenarios=[
        Scenario(
            TWO,
            place("p1", at="table", t="0.3s..0.8s", **CROOKED),
            remove("p1", when=after_event("alignment measured", "p1"), delay=ROBOT),
            place("p2", at="table", when=after_event("part removed", "p1"), delay="0.5s..1s", **CROOKED),
            remove("p2", when=after_event("alignment measured", "p2"), delay=ROBOT),
            duration="9s",
            description="a crooked object is aligned and taken away by the robot; a second one after it",
        ),
        Scenario(
            STAYS,
            place("p1", at="table", t="0.3s..0.8s", **CROOKED),
            duration="12s",
            description="the aligned object is left on the table for 10 s",
        ),
        Scenario(
            BRIEF,
            place("brief", at="table", t="0.3s..0.8s", **CROOKED),
            remove("brief", when=after_event("part placed", "brief"), delay="0.3s..0.9s"),
            duration="3s",
            description="an object seen for less than 1 s is taken away again",
        ),
        Scenario(
            JAMMED,
            place("p1", at="table", t="0.3s..0.8s", **CROOKED),
            JAM_PISTON("PIEST", when=after_event("part placed", "p1"), delay="1.15s..1.35s"),
            outside={FAULTS: FAULT_WORDS},
            duration="5s",
            description="the piston rod sticks half-way out (the task defines no timeout: the program waits)",
        ),
        Scenario(
            DEAD,
            wire_break("PIEST_SNIMAC_VZAD", t="0s"),
            place("p1", at="table", t="0.3s..0.8s", **CROOKED),
            outside={FAULTS: FAULT_WORDS},
            duration="6s",
            description="the rear end-position sensor's wire is broken: the piston is never seen at home",
        ),
    ],
    checks=[
        # criterion 1
        only(
            rises("PIEST_CHOD_VPRED")
            .between("1s", "1s + 2 scans")
            .after(rises("OS"))
            .named("the piston starts 1 s after the object is detected"),
            TWO,
            STAYS,
        ),
        # criterion 2
        only(
            count(event("piston extended")).equals(2).named("one full stroke per object (two objects, two strokes)"),
            TWO,
        ),
        only(count(event("piston retracted")).equals(2).named("the piston is back at the rear after each stroke"), TWO),
        only(final("PIEST_CHOD_VPRED").equals(0).named("the piston output is off at the end"), TWO, STAYS, BRIEF, DEAD),
        # criterion 3
        only(
            event_data("alignment measured", "gap_mm").at_most(1.0).named("each object ends within 1 mm of the fence"),
            TWO,
            STAYS,
        ),
        only(
            event_data("alignment measured", "angle_deg").at_most(2.0).named("each object ends square within 2°"),
            TWO,
            STAYS,
        ),
        # criterion 4
        only(
            count(event("piston extended")).equals(1).named("no second stroke while the object stays (10 s)"),
            STAYS,
        ),
        only(
            holds("OBJ_ZAROVNANY").to_the_end().named("OBJ_ZAROVNANY stays TRUE while the aligned object is there"),
            STAYS,
        ),
        # criterion 5
        only(
            never(rises("PIEST_CHOD_VPRED")).named("an object seen for less than 1 s gets no stroke"),
            BRIEF,
        ),
        # criterion 6
        only(
            count(event("alignment measured")).equals(2).named("a new object is aligned again"),
            TWO,
        ),
        # a jammed piston aligns nothing: the program must not say it did
        only(never(on("OBJ_ZAROVNANY")).named("a jammed piston is not reported as an aligned object"), JAMMED),
        # OBJ_ZAROVNANY tells the robot it may take the object: the plate must be out of its way by then
        only(
            never(all_of("OBJ_ZAROVNANY", off("PIEST_SNIMAC_VZAD"))).named(
                "OBJ_ZAROVNANY only once the piston is back at the rear"
            ),
            TWO,
            STAYS,
        ),
        only(
            never(on("OBJ_ZAROVNANY")).named("with the rear sensor dead nothing is reported aligned"),
            DEAD,
        ),
    ],
    requirements={
        "the piston starts 1 s after the object is detected": (
            "The piston starts forward 1 s after the object is detected (at most 2 scans later)"
        ),
        "one full stroke per object (two objects, two strokes)": "makes one full stroke per object",
        "the piston is back at the rear after each stroke": "forward to the front sensor and back to the rear",
        "the piston output is off at the end": "its output is off once the stroke is done",
        "each object ends within 1 mm of the fence": "Each object ends against the fence (within 1 mm)",
        "each object ends square within 2°": "and square (within 2°)",
        "no second stroke while the object stays (10 s)": "and none more while the object stays",
        "OBJ_ZAROVNANY stays TRUE while the aligned object is there": "stays while the aligned object is there",
        "an object seen for less than 1 s gets no stroke": "An object seen for less than 1 s gets no stroke",
        "a new object is aligned again": "the next object is aligned again",
        "a jammed piston is not reported as an aligned object": (
            "so it never comes when the piston jams or the rear sensor is dead"
        ),
        "OBJ_ZAROVNANY only once the piston is back at the rear": (
            "it comes only once the piston is back at the rear sensor"
        ),
        "with the rear sensor dead nothing is reported aligned": (
            "so it never comes when the piston jams or the rear sensor is dead"
        ),
    },
    solutions=[
        solution(NUMBER, "reference", explanation="solution 1 (Figs. 4.108-4.112) with the resets the text omits"),
        solution(NUMBER, "solution-2", "alternative", "solution 2 (Figs. 4.114-4.120): step variable KROK"),
        solution(
            NUMBER,
            "wrong-as-printed",
            "wrong",
            "solution 1 as printed: OBJ_ZAROVNANY (and BOL_VPRED) are never reset, so the next object is never aligned",
            fails=("a new object is aligned again",),
        ),
        solution(
            NUMBER,
            "wrong-no-bol-vpred",
            "wrong",
            "without BOL_VPRED, back at the rear the piston goes out again in the scan that ends the cycle, and stays "
            "out",
            fails=("no second stroke while the object stays (10 s)", "the piston output is off at the end"),
        ),
        solution(
            NUMBER,
            "wrong-solution-2-no-delay",
            "wrong",
            "solution 2 as its text reads, without the 1 s delay: the stroke comes within a scan of the detection, and "
            "an object that only passes is struck",
            fails=(
                "the piston starts 1 s after the object is detected",
                "an object seen for less than 1 s gets no stroke",
            ),
        ),
        solution(
            NUMBER,
            "wrong-timer-keeps-running",
            "wrong",
            "(not from the textbook) TON input without NOT OBJ_ZAROVNANY: the aligned object is struck again and again",
            fails=("no second stroke while the object stays (10 s)",),
        ),
        solution(
            NUMBER,
            "wrong-coil-not-latch",
            "wrong",
            "(a slip) the valve as a coil ZAROVNAJ AND NOT front: it reopens as soon as the plate leaves the front "
            "sensor and hammers there",
            fails=("the piston is back at the rear after each stroke",),
        ),
        solution(
            NUMBER,
            "wrong-timed-stroke",
            "wrong",
            "(a slip) a guessed 0.3 s stroke instead of the front sensor: the plate barely reaches the object, which "
            "is left crooked and off the fence",
            fails=("each object ends within 1 mm of the fence",),
        ),
        solution(
            NUMBER,
            "wrong-done-off-the-front",
            "wrong",
            "(a slip) solution 2 with step 2 ended when the front sensor is released, not at the rear: 'aligned' "
            "while the plate is still on its way back, where the robot would meet it",
            fails=(
                "OBJ_ZAROVNANY only once the piston is back at the rear",
                "with the rear sensor dead nothing is reported aligned",
            ),
        ),
    ],
    spec_equivalent={
        **{
            m: (
                "ZAROVNAJ is set at the end of the scan in which the TON expires, so the stroke starts a scan later: "
                "inside criterion 1's 1 s … 1 s + 2 scans after OS"
            )
            for m in ("OB1: networks delay and align swapped", "OB1: network delay moved to the end")
        },
        "t.PIEST_SNIMAC_VZAD and (not t.BOL_VPRED) → not t.BOL_VPRED": (
            "the forward stroke started without the rear sensor: the piston is back at the rear whenever an object "
            "has waited its 1 s (the robot takes the object only after the plate is back), and with the rear sensor "
            "dead it strokes and then waits, as the textbook's solution 2 does; nothing is reported aligned either way"
        ),
    },
    notes=(
        "Addresses, NO wiring and the memory addresses are proposals (the textbook gives none). The rung 3 reset of "
        "OBJ_ZAROVNANY and the reset of BOL_VPRED are the text's omissions (§4 item 6) and part of the reference. "
        "The P contact of branch c is evaluated in every scan, as S7's -|P|- does; the branch gates its result. "
        "Criterion 1's window is 1 s … 1 s + 2 scans after OS (the TON expires in the first scan with ET ≥ 1 s). "
        "Objects are placed 0–15 mm off the fence and turned ±15° (drawn with the seed); the robot takes an "
        "object 0.5–1 s after the plate is back. The jammed piston is informational in the task; the check there is "
        "only that nothing is reported aligned. So with the rear sensor dead (a broken wire): the program cannot see "
        "the piston home and must not say the object is aligned (solution 1 never starts the stroke, solution 2 "
        "strokes and waits in step 2). OBJ_ZAROVNANY tells the robot it may take the object, so it may be TRUE only "
        "while the rear sensor reports the piston home."
    ),
)
