"""6.3.3 Task 3 — one press stroke. Plant: PUNCH."""

from __future__ import annotations

from exercises._common import solution
from exercises._punch import (
    MODEL,
    PRESS_JAM,
    PUNCH_IO,
    AwaitingStroke,
    PerObject,
    PerVisit,
    constant,
    cycles,
    edge_bits,
    interlocks,
    machine_safe,
    strokes_land_on_objects,
    strokes_on,
)
from plants import Punch
from plcsim.check import all_of, assumes, count, final, never, off, parts_at_once, rises
from plcsim.exercise import IO, Exercise, only
from plcsim.scenario import FAULTS, Scenario, after_event, chatter, free_motor, held, jam_motor, place, remove

NUMBER = "6.3.3"
AT_OS2 = "The operator puts the object straight under the press (at OS2) and takes it away there"
"""The operating condition the task states: one object at OS2 at a time (an exchange takes one away first)."""
BOUNCING = (
    "KS1 and KS2 are contacts and may bounce: a change can come with a few extra toggles of 2 to 10 ms, and every "
    "object still gets exactly one stroke."
)
"""The task's words for the scenario 'bouncing limit switches' (``Scenario(outside={FAULTS: ...})``)."""
OBJECTS = 3
BOUNCE = "bouncing limit switches"
EXCHANGED = "object exchanged while the ram goes up"
STARTS = "The press starts down in the scan in which it is at the top (KS1) with an object at OS2"
REVERSES = "reverses in the scan that sees KS2"
STOPS = "stops in the scan that sees KS1 again"
ONCE = "The sequence may start again only after the object has been removed and a new one loaded"
DOWN_FOR_AN_OBJECT = "moves the punching device down and then up when an object is detected by OS2"
TAKEN = "If the object is taken away while the press goes down, the press finishes its stroke and waits at the top"
HOLDS = ("4s", "4.5s", "4.2s")  # the operator takes the object away this long after placing it (a stroke: 2.7 s)

EXERCISE = Exercise(
    number=NUMBER,
    slug="punch-stroke",
    title="Punching machine 3: one press stroke",
    title_sk="Slovné zadanie 3 – Lisovací stroj s dopravníkom",
    task=(
        MODEL + "\n"
        "Task: create a program that moves the punching device down and then up when an object is detected by OS2. "
        "The sequence may start again only after the object has been removed and a new one loaded. It is similar to "
        "task 1, except that the object does not move: the punching part of the model moves. The operator puts the "
        "object straight under the press (at OS2) and takes it away there; they may take a punched object away, and "
        "put the next one there, while the press is still going back up: the next stroke starts only once the press "
        "is at the top (KS1), and the new object gets its one stroke. The press starts down in the scan in which it "
        "is at the top (KS1) with an object at OS2 that it has not punched yet, reverses in the scan that sees KS2 "
        "and stops in the scan that sees KS1 again. If the object is taken away while the press goes down, the press "
        "finishes its stroke and waits at the top. Remember that the press has been down for the object in the bit "
        "OBJEKT_BOL_DOLE; the removal is the rising edge of OS2 (edge memory bit POM_P_OS2). "
        + BOUNCING
        + " "
        + PRESS_JAM
    ),
    io=[
        *PUNCH_IO,
        IO("OBJEKT_BOL_DOLE", "the press has been down for this object", "Bool", "%M0.1", comment="address proposed"),
        *edge_bits("POM_P_OS2"),
    ],
    rig=Punch,
    scenarios=[
        Scenario(
            "three objects",
            *cycles(OBJECTS, at="OS2", rest=HOLDS),
            duration="22s",
            description="three objects, one after the other, put under the press at OS2 and taken away 4..4.5 s "
            "later; the next is put there 1..2 s after the removal",
        ),
        Scenario(
            BOUNCE,
            chatter("KS1", t="0s"),
            chatter("KS2", t="0s"),
            *cycles(OBJECTS, at="OS2", rest=HOLDS),
            outside={FAULTS: BOUNCING},
            duration="22s",
            description="the limit switches are contacts and bounce: each change of KS1 and KS2 comes with 3..5 "
            "extra toggles of 2..10 ms; three objects as in 'three objects'",
        ),
        Scenario(
            "jammed press",
            place("p1", at="OS2", t="0.3s..0.8s"),
            jam_motor("M2_DOLE", when=after_event("part entered", "OS2"), delay="0.4s..0.9s"),
            free_motor("M2_DOLE", when=after_event("motor jammed"), delay="1.5s..3s"),
            remove("p1", when=held("OS2", "7s")),
            place("p2", at="OS2", when=after_event("part removed", "p1"), delay="1s..2s"),
            remove("p2", when=held("OS2", "4s")),
            outside={FAULTS: PRESS_JAM},
            duration="18s",
            description="a fault: the press jams on its way down (KS2 is not reached) and is freed 1.5..3 s later; "
            "the stroke then completes; a second object follows",
        ),
        Scenario(
            EXCHANGED,
            place("p1", at="OS2", t="0.3s..0.8s"),
            remove("p1", when=after_event("press stroke"), delay="0.3s..0.5s"),
            place("p2", at="OS2", when=after_event("part removed", "p1"), delay="0.2s..0.4s"),
            remove("p2", when=held("OS2", "4s")),
            duration="10s",
            description="the operator takes the punched object away while the ram goes back up (0.3..0.5 s after "
            "its stroke) and puts a new one under the press 0.2..0.4 s later, before the ram is back at KS1: the "
            "new object gets its one stroke once the press is at the top",
        ),
        Scenario(
            "object taken during the stroke",
            place("p1", at="OS2", t="0.3s..0.8s"),
            remove("p1", when=after_event("part entered", "OS2"), delay="0.5s..1s"),
            duration="6s",
            description="the operator takes the object away while the press is on its way down",
        ),
    ],
    checks=[
        # criterion 1
        never(all_of(AwaitingStroke(), "KS1", off("M2_DOLE")))
        .named("the press starts down within 1 scan for an object at OS2")
        .grades(STARTS),
        never(all_of("KS2", "M2_DOLE")).named("the press stops at KS2 within 1 scan").grades(REVERSES),
        never(all_of("KS2", off("M2_HORE"))).named("the press goes back up from KS2 within 1 scan").grades(REVERSES),
        never(all_of("KS1", "M2_HORE")).named("the press stops at KS1 within 1 scan").grades(STOPS),
        # criteria 2 and 3
        only(
            PerVisit("every object under the press is punched exactly once", constant(1)).grades(ONCE),
            "three objects",
            "jammed press",
            BOUNCE,
            EXCHANGED,
        ),
        only(
            PerObject("every object gets exactly one stroke", "was punched", strokes_on, constant(1)).grades(ONCE),
            "three objects",
            "jammed press",
            BOUNCE,
            EXCHANGED,
        ),
        only(strokes_land_on_objects().grades(DOWN_FOR_AN_OBJECT), "three objects", "jammed press", BOUNCE, EXCHANGED),
        only(
            count(rises("M2_DOLE"))
            .equals(OBJECTS)
            .named("the press starts once per object, never without one")
            .grades(ONCE),
            "three objects",
        ),
        *interlocks(belt=False),
        *machine_safe(),
        only(
            final("KS1").equals(1).named("the press is back at KS1 at the end").grades(TAKEN),
            "object taken during the stroke",
        ),
    ],
    solutions=[
        solution(
            NUMBER,
            "reference",
            explanation="S M2_DOLE for an object at OS2 with the press at KS1 and not OBJEKT_BOL_DOLE; at KS2 "
            "reverse and S OBJEKT_BOL_DOLE; R M2_HORE at KS1; the removal edge of OS2 clears OBJEKT_BOL_DOLE",
        ),
        solution(
            NUMBER,
            "wrong-no-helper-bit",
            "wrong",
            "(not from the textbook) without the OBJEKT_BOL_DOLE test the press strokes again and again while the "
            "object lies at OS2",
            fails=("every object under the press is punched exactly once",),
        ),
        solution(
            NUMBER,
            "wrong-no-ks1-interlock",
            "wrong",
            "(a slip, not from the textbook) the stroke starts without the KS1 test: an object exchanged while the "
            "ram goes back up starts it at once, and the press is driven down and up together",
            fails=("the press is never driven down and up at once", "the machine reports no interlock violation"),
        ),
        solution(
            NUMBER,
            "wrong-no-stop-at-top",
            "wrong",
            "(not from the textbook) no R M2_HORE at KS1: the press runs into its upper end stop and stalls",
            fails=("the press is never driven against an end stop", "the press stops at KS1 within 1 scan"),
        ),
        solution(
            NUMBER,
            "wrong-ks1-lower",
            "wrong",
            "the model text's KS1 = lower, KS2 = upper (text issue 12), on a model wired as the solutions use it: "
            "KS1 at the top is taken for 'down', the press is driven into its upper end stop, nothing is punched",
            fails=(
                "every object under the press is punched exactly once",
                "the press is never driven against an end stop",
            ),
        ),
    ],
    conditions=[assumes(AT_OS2, parts_at_once(1))],
    spec_equivalent={
        "P(t.OS2, 'POM_P_OS2') → t.OS2": (
            "OBJEKT_BOL_DOLE is cleared in every scan without an object at OS2 instead of once as it leaves: 'the "
            "sequence may restart only after the object has been removed and a new one loaded' holds either way "
            "(after an object taken during the stroke it even lets the next one be punched, as criterion 3 asks)"
        ),
    },
    notes=(
        "The object is put straight under the press: the OS2 station places it 5 mm past the press axis (the "
        "operator's ±5 mm), so it always cuts the OS2 beam and lies under the tool. A stroke is counted by the plant "
        "when the tool tip passes 75 mm (the object's top is at 70 mm), on the object whose extent holds the press "
        "axis. 'Jammed press' is a fault of the machine, not of the program: the textbook's program keeps M2_DOLE on "
        "while the press stands (it has no watchdog) and finishes the stroke once the press is freed. 'Object taken "
        "during the stroke' grades only what must hold then: the press finishes its stroke and waits at KS1 (the "
        "textbook's OBJEKT_BOL_DOLE is set after the removal edge, so an object put there next would not be punched; "
        "the textbook does not consider this case). 'Object exchanged while the ram goes up' is the case a program "
        "without the KS1 test in the stroke's start gets wrong (it drives the press down while it still goes up), "
        "and one that never punches the new object fails criterion 3 (after removal and placement of a new object, "
        "exactly one new stroke). 'Bouncing limit switches': KS1 and KS2 are contacts (the model text's 'kontaktné "
        "snímače'); the textbook's program only sets and resets on their levels, so a bounce repeats a SET or a "
        "RESET and changes nothing."
    ),
)
