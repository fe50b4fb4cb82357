"""6.3.4 Task 4 — task 3 integrated into task 2: one press stroke at every move to OS2. Plant: PUNCH."""

from __future__ import annotations

from exercises._common import solution
from exercises._punch import (
    COUNT_RUNG_MOVED,
    MODEL,
    PRESS_JAM,
    PRESS_WORDS,
    PUNCH_IO,
    TAKEN_FROM_THE_PRESS,
    constant,
    counts,
    cycles,
    edge_bits,
    parameter,
    punching_checks,
    shuttle_words,
    taken_from_the_press,
)
from plants import Punch
from plcsim.check import assumes, parts_at_once
from plcsim.exercise import IO, Exercise
from plcsim.scenario import FAULTS, Scenario, after_event, free_motor, jam_motor

NUMBER = "6.3.4"
REQUIRED = "M1_ZIADANY_POCET"
WHOLE = ("one move, then two", "jammed press")

IO_TABLE = [
    *PUNCH_IO,
    *counts(REQUIRED, "M1_AKTUALNY_POCET"),
    IO("OBJEKT_PRI_OS2", "the required number of moves is reached", "Bool", "%M0.0", comment="address proposed"),
    IO("OBJEKT_BOL_DOLE", "the press has been down in this visit", "Bool", "%M0.1", comment="address proposed"),
    *edge_bits("POM_P_OS1", "POM_N_OS2", "POM_P_OS2"),
]


EXERCISE = Exercise(
    number=NUMBER,
    slug="punch-shuttle-stroke",
    title="Punching machine 4: a press stroke at every move",
    title_sk="Slovné zadanie 4 – Lisovací stroj s dopravníkom",
    task=(
        MODEL + "\n"
        "Task: integrate the program of task 3 into the program of task 2: the object makes M1_ZIADANY_POCET moves "
        "to OS2 and back and is punched once at every visit to OS2; then it waits at OS1 for its removal. An object "
        "detected at OS2 must not be sent back before the punching is finished: the press must have been down "
        "(OBJEKT_BOL_DOLE) and have returned to the upper position; once the press is back at KS1, the object is "
        "sent back at once (in the same scan). Keep the moves made so far in M1_AKTUALNY_POCET, 0 again once the "
        "object has been removed, as in task 2. One object at a time; a required count of zero need not be handled."
        + " "
        + shuttle_words(reverse_at_os2=False)
        + " "
        + PRESS_WORDS
        + " "
        + PRESS_JAM
    ),
    io=IO_TABLE,
    rig=Punch,
    scenarios=[
        Scenario(
            "one move, then two",
            *cycles(2, writes={1: {REQUIRED: 1}, 2: {REQUIRED: 2}}),
            duration="42s",
            description="the first object with M1_ZIADANY_POCET = 1, the second (loaded after the first was "
            "taken away) with 2: each visit to OS2 gets one stroke",
        ),
        Scenario(
            "jammed press",
            *cycles(1, writes={1: {REQUIRED: 1}}),
            jam_motor("M2_DOLE", when=after_event("part entered", "OS2"), delay="0.4s..0.9s"),
            free_motor("M2_DOLE", when=after_event("motor jammed"), delay="1.5s..3s"),
            outside={FAULTS: PRESS_JAM},
            duration="18s",
            description="a fault: the press jams on its way down and is freed 1.5..3 s later; the belt must wait",
        ),
        Scenario(
            TAKEN_FROM_THE_PRESS,
            *taken_from_the_press({REQUIRED: 2}),
            duration="14s",
            description="M1_ZIADANY_POCET = 2; the operator takes the object from under the press while the ram goes "
            "back up after its first stroke (0.3..1.2 s after it): the ram returns to KS1 and strikes no more",
        ),
    ],
    checks=punching_checks(constant(1), parameter(REQUIRED), "exactly one stroke", (REQUIRED,), WHOLE),
    conditions=[assumes("One object at a time", parts_at_once(1))],
    requirements={
        "every stay under the press gets exactly one stroke": "is punched once at every visit to OS2",
        "every stroke comes down on an object": "The press goes down only for an object at OS2",
        "every object is punched M1_ZIADANY_POCET times": "is punched once at every visit to OS2",
        "every object is carried to OS2 M1_ZIADANY_POCET times": "the object makes M1_ZIADANY_POCET moves to OS2",
        "the belt reverses within 1 scan once the press is back at KS1 after the last stroke": (
            "once the press is back at KS1, the object is sent back at once (in the same scan)"
        ),
    },
    solutions=[
        solution(
            NUMBER,
            "reference",
            explanation="6.3.2 solution 2 as rungs 1-4, 6.3.3 as rungs 5-7; rung 2 reverses only when "
            "OBJEKT_BOL_DOLE AND KS1; OBJEKT_BOL_DOLE cleared when the object leaves OS2",
        ),
        solution(
            NUMBER,
            "solution-steps",
            "alternative",
            "(not from the textbook) a step sequencer on one Int step: forward, down, up, back; taken from under the "
            "press, the object is never seen back at OS1 and the belt runs back towards it (the task does not say "
            "what the belt should do then)",
        ),
        solution(
            NUMBER,
            "wrong-no-ks1",
            "wrong",
            "rung 2 without KS1: the belt carries the object away while the press is still down (the textbook: "
            "the object would start moving during punching, damage to product and machine)",
            fails=(
                "the belt never runs while the press is away from KS1 or moving",
                "no object is damaged by the press",
            ),
        ),
        solution(
            NUMBER,
            "wrong-no-reset-on-leaving",
            "wrong",
            "(not from the textbook) OBJEKT_BOL_DOLE never cleared: the second visit gets no stroke",
            fails=("every stay under the press gets exactly one stroke",),
        ),
    ],
    spec_equivalent=COUNT_RUNG_MOVED,
    notes=(
        "The textbook builds task 4 from task 2's solution 2 (ADD), so OBJEKT_PRI_OS2 and M1_AKTUALNY_POCET are "
        "kept. Criterion 2 is graded twice: on the PLC's outputs (the belt never runs while the press is away from "
        "KS1 or driven) and on the machine's word (no interlock violation, no damaged object). 'Jammed press' is a "
        "fault of the machine: the program must keep the belt still until the stroke is finished. 'Object taken from "
        "under the press' grades what the program must do then: no new stroke (the press goes down only for an "
        "object at OS2) and the ram back at KS1. It grades neither what the belt does then (the task does not say: "
        "the textbook's program stands, a step sequencer waiting for the object's return may run the belt back to "
        "OS1) nor the moves and their count: the textbook's removal is the rising edge of OS1 with the belt "
        "standing, so its M1_AKTUALNY_POCET keeps the move of the object taken, and an object loaded next would make "
        "only the moves left (with one required it would not start at all: the program takes it for the returned "
        "object); the task does not say what a removal at the press should do to the series, so the scenario loads "
        "no next object. A removal while the belt carries the object is 6.3.2's scenario: no sensor sees it."
    ),
)
