"""4.3.9 Conveyors 1 (three conveyors, occupancy states). Plant: CONV3.

Mutation testing (``plcsim mutate 4.3.9``): two mutants survive, both start a conveyor one scan later than
the reference and change nothing else; ``spec_equivalent`` says why they are correct programs. The
equivalent ones are swaps of adjacent networks that never act in the same scan (a load at D1_OS and an
arrival at D2_OS, say), and ``P(D3_OS) -> D3_OS``: D3_VPRED falls in the scan that sets D3_OBS, so the
level acts once, like the edge.
"""

from __future__ import annotations

from exercises._common import solution
from exercises._truth import Parts, flag_matches
from plants import Conv3
from plcsim.check import all_of, always, any_of, count, event, falls, implies, never, off, rises
from plcsim.exercise import IO, Exercise, only
from plcsim.scenario import Scenario, after_event, held, place, remove

NUMBER = "4.3.9"

HAND = ("hand",)  # the operator's hand, modelled as a block put in front of a sensor
ON_D1 = Parts("D1_OS", "D2_OS", HAND, "objects on D1")
ON_D2 = Parts("D2_OS", "D3_OS", HAND, "objects on D2")
ON_D3 = Parts("D3_OS", None, HAND, "objects on D3")

EXERCISE = Exercise(
    number=NUMBER,
    slug="conveyors-1",
    title="Conveyors 1 (three conveyors, occupancy states)",
    title_sk="Príklad 9 – Ovládanie dopravníkov 1",
    task=(
        "Three conveyors D1, D2, D3 in series are driven forward by D1_VPRED, D2_VPRED and D3_VPRED (conveyor n "
        "forward). Each has an optical sensor that sees the objects it carries: D1_OS, D2_OS, D3_OS (optical sensor "
        "on conveyor n), all wired as normally open contacts. A sensor sees the object entering its conveyor from "
        "the previous one; once the object has left the sensor's beam the conveyor must still be known to be "
        "occupied.\n"
        "Task: create conveyor states D1_OBS, D2_OBS, D3_OBS (conveyor n occupied) that stay TRUE while the object "
        "is on the conveyor even where no sensor sees it, and with them move objects from D1 to D3: an object moves "
        "to the next conveyor only if its conveyor is occupied and the next one is free. At the last position (D3) "
        "the occupancy is cleared when the object is removed by hand. Objects are loaded at D1_OS. Edge memory "
        "bits: SB1-SB3 (and SB4, see the notes). A conveyor runs only to carry its object to a free next one (or "
        "to take one from the previous); it stops in the scan in which the object reaches the next sensor (D3 in the "
        "scan in which D3_OS sees it). Never more than one object is on a conveyor, and none falls off. A hand "
        "that shades a sensor of the stopped line occupies nothing and starts nothing."
    ),
    io=[
        IO("D1_VPRED", "conveyor 1 forward", "Bool", "%Q0.0"),
        IO("D2_VPRED", "conveyor 2 forward", "Bool", "%Q0.1"),
        IO("D3_VPRED", "conveyor 3 forward", "Bool", "%Q0.2"),
        IO("D1_OS", "optical sensor on D1 (loading place)", "Bool", "%I0.0", "NO"),
        IO("D2_OS", "optical sensor on D2", "Bool", "%I0.1", "NO"),
        IO("D3_OS", "optical sensor on D3 (removal place)", "Bool", "%I0.2", "NO"),
        IO("D1_OBS", "D1 occupied", "Bool", "%M0.0"),
        IO("D2_OBS", "D2 occupied", "Bool", "%M0.1"),
        IO("D3_OBS", "D3 occupied", "Bool", "%M0.2"),
        IO("SB1", "edge memory bit", "Bool", "%M2.0"),
        IO("SB2", "edge memory bit", "Bool", "%M2.1"),
        IO("SB3", "edge memory bit", "Bool", "%M2.2"),
        IO(
            "SB4",
            "edge memory bit (falling edge of D3_OS)",
            "Bool",
            "%M2.3",
            comment="not in the textbook's table (text issue): P and N on D3_OS need two bits",
        ),
    ],
    rig=Conv3,
    scenarios=[
        Scenario(
            "one object and a hand",
            place("hand", at="D2_OS", t="0.3s..0.8s", noise=False),
            remove("hand", t="1.5s..2s"),
            place("p1", at="D1_OS", t="2.5s..3s"),
            remove("D3_OS", when=held("D3_OS", "1s")),
            duration="18s",
            description="the line is stopped and empty; a hand shades D2_OS for about a second; then one "
            "object is loaded, carried to D3_OS and taken away",
        ),
        Scenario(
            "a hand at D3_OS",
            place("hand", at="D3_OS", t="0.3s..0.8s", noise=False),
            remove("hand", t="1.5s..2s"),
            duration="4s",
            description="the line is stopped and empty; a hand shades D3_OS for about a second: it occupies nothing "
            "and starts nothing",
        ),
        Scenario(
            "queue of three",
            place("p1", at="D1_OS", t="0.3s..0.8s"),
            place("p2", at="D1_OS", when=after_event("part entered", "D2_OS"), delay="0.5s..1.5s"),
            place("p3", at="D1_OS", when=held("D2_OS", "1s"), delay="0s..0.5s"),
            remove("D3_OS", when=held("D3_OS", "7s")),
            duration="35s",
            description="p1 goes to D3 and waits there; p2 is loaded once D1 is free and waits at D2_OS; p3 "
            "is loaded and waits at D1_OS; p1 is taken away and the queue moves up one place",
        ),
    ],
    checks=[
        # criterion 1: the occupancy rules
        always(implies("D1_VPRED", all_of("D1_OBS", off("D2_OBS")))).named(
            "D1 runs only while D1 is occupied and D2 free"
        ),
        always(implies("D2_VPRED", any_of(all_of("D1_OBS", off("D2_OBS")), all_of("D2_OBS", off("D3_OBS"))))).named(
            "D2 runs only to take an object from D1 or to pass its own to a free D3"
        ),
        always(implies("D3_VPRED", all_of("D2_OBS", off("D3_OBS")))).named(
            "D3 runs only while D2 is occupied and D3 free"
        ),
        # criteria 4 and 6: the states follow the objects
        always(flag_matches("D1_OBS", ON_D1)).named("D1_OBS is TRUE exactly while an object is on D1"),
        always(flag_matches("D2_OBS", ON_D2)).named("D2_OBS is TRUE exactly while an object is on D2"),
        always(flag_matches("D3_OBS", ON_D3)).named("D3_OBS is TRUE exactly while an object is on D3"),
        always(all_of(ON_D1 <= 1, ON_D2 <= 1, ON_D3 <= 1)).named("never more than one object on a conveyor"),
        never(event("part fell off")).named("no object falls off"),
        # criterion 2: stopping at the sensors
        *(
            only(check, "one object and a hand", "queue of three")  # no object reaches a sensor in 'a hand at D3_OS'
            for check in (
                falls("D1_VPRED")
                .within("1 scan")
                .after(rises("D2_OS"), provided=ON_D2 > 0)
                .named("D1 stops within 1 scan when the object reaches D2_OS"),
                falls("D3_VPRED")
                .within("1 scan")
                .after(rises("D3_OS"))
                .named("D3 stops within 1 scan when the object reaches D3_OS"),
            )
        ),
        only(
            falls("D2_VPRED")
            .within("1 scan")
            .after(rises("D3_OS"))
            .named("D2 stops within 1 scan when the only object reaches D3_OS"),
            "one object and a hand",
        ),
        only(
            count(event("part entered", "D3_OS")).equals(1).named("the object is carried to D3_OS"),
            "one object and a hand",
        ),
        # criterion 5: a hand at a stopped line
        only(
            never(any_of("D2_OBS", "D1_VPRED", "D2_VPRED", "D3_VPRED"))
            .during("0s", "2.4s")
            .named("a hand at D2_OS on the stopped line occupies nothing and starts nothing"),
            "one object and a hand",
        ),
        # criterion 3: the queue
        only(
            count(event("part entered", "D3_OS"))
            .equals(2)
            .named("after the removal at D3 the next object moves up to D3"),
            "queue of three",
        ),
        only(
            count(event("part entered", "D2_OS"))
            .equals(3)
            .named("after the removal at D3 the object waiting at D1 moves up to D2"),
            "queue of three",
        ),
    ],
    requirements={
        "D1 runs only while D1 is occupied and D2 free": (
            "an object moves to the next conveyor only if its conveyor is occupied and the next one is free"
        ),
        "D2 runs only to take an object from D1 or to pass its own to a free D3": (
            "A conveyor runs only to carry its object to a free next one (or to take one from the previous)"
        ),
        "D3 runs only while D2 is occupied and D3 free": (
            "A conveyor runs only to carry its object to a free next one (or to take one from the previous)"
        ),
        "D1_OBS is TRUE exactly while an object is on D1": (
            "that stay TRUE while the object is on the conveyor even where no sensor sees it"
        ),
        "D2_OBS is TRUE exactly while an object is on D2": (
            "that stay TRUE while the object is on the conveyor even where no sensor sees it"
        ),
        "D3_OBS is TRUE exactly while an object is on D3": (
            "that stay TRUE while the object is on the conveyor even where no sensor sees it"
        ),
        "never more than one object on a conveyor": "Never more than one object is on a conveyor",
        "no object falls off": "and none falls off",
        "D1 stops within 1 scan when the object reaches D2_OS": (
            "it stops in the scan in which the object reaches the next sensor"
        ),
        "D3 stops within 1 scan when the object reaches D3_OS": "D3 in the scan in which D3_OS sees it",
        "D2 stops within 1 scan when the only object reaches D3_OS": (
            "it stops in the scan in which the object reaches the next sensor"
        ),
        "the object is carried to D3_OS": "with them move objects from D1 to D3",
        "a hand at D2_OS on the stopped line occupies nothing and starts nothing": (
            "A hand that shades a sensor of the stopped line occupies nothing and starts nothing"
        ),
        "after the removal at D3 the next object moves up to D3": "with them move objects from D1 to D3",
        "after the removal at D3 the object waiting at D1 moves up to D2": "with them move objects from D1 to D3",
    },
    solutions=[
        solution(
            NUMBER,
            "reference",
            explanation="occupancy states set on the sensors' rising edges while the "
            "receiving conveyor runs; a conveyor runs while it is occupied and the next one free",
        ),
        solution(
            NUMBER, "loading-edge", "alternative", "as the reference, with loading on the rising edge of D1_OS (SB1)"
        ),
        solution(
            NUMBER,
            "wrong-no-running-condition",
            "wrong",
            "arrivals without the D2_VPRED / D3_VPRED contact: a hand at D2_OS occupies D2 and starts the line",
            fails=(
                "a hand at D2_OS on the stopped line occupies nothing and starts nothing",
                "D2_OBS is TRUE exactly while an object is on D2",
            ),
        ),
        solution(
            NUMBER,
            "wrong-no-edge",
            "wrong",
            "arrival on D2 on the level of D2_OS: while the leaving object is in the beam, D1_OBS is reset in "
            "every scan although D1 carries an object",
            fails=("D1_OBS is TRUE exactly while an object is on D1",),
        ),
        solution(
            NUMBER,
            "wrong-shared-aux",
            "wrong",
            "(from the tag table's three edge bits, not a textbook solution) P and N on D3_OS share SB3: the N "
            "never fires, D3 stays occupied after the removal",
            fails=(
                "D3_OBS is TRUE exactly while an object is on D3",
                "after the removal at D3 the next object moves up to D3",
            ),
        ),
    ],
    spec_equivalent={
        "OB1: network loading moved to the end": (
            "the run networks see D1_OBS a scan after it is set, so D1 starts one scan later: the spec bounds when "
            "a conveyor stops (criterion 2, 'within 1 scan'), not when it starts"
        ),
        "OB1: network removal_d3 moved to the end": (
            "after the removal at D3 the queue starts a scan later: the spec bounds when a conveyor stops "
            "(criterion 2, 'within 1 scan'), not when it starts"
        ),
    },
    notes=(
        "Text issue: the tag table has SB1-SB3 for three edges (D2_OS rising, D3_OS rising, D3_OS falling), and SB1 "
        "suggests an edge on D1_OS as well; P and N on D3_OS must not share a bit, so SB4 (%M2.3) is added "
        "(wrong-shared-aux shows what sharing does). %M0.0-%M0.2 would collide with clock memory at MB0: this "
        "exercise enables no clock memory. 'Never collides' is graded as 'never more than one object on a conveyor' "
        "and the truth of the occupancy states: the plant reports no part-on-part contact. The true occupancy is "
        "taken from the plant's events in the textbook's sense (an object belongs to D1 until D2_OS sees it, and "
        "so on); the hand (a block placed at D2_OS and removed) is not an object."
    ),
)
