"""6.3.5 Task 5 — the required number of press strokes (an Int parameter). Plant: PUNCH."""

from __future__ import annotations

from exercises._common import solution
from exercises._punch import (
    COUNT_RUNG_MOVED,
    MODEL,
    PRESS_JAM,
    PRESS_WORDS,
    PUNCH_IO,
    TAKEN_FROM_THE_PRESS,
    counts,
    cycles,
    edge_bits,
    parameter,
    product,
    punching_checks,
    shuttle_words,
    taken_from_the_press,
)
from plants import Punch
from plcsim.check import all_of, assumes, never, parts_at_once, value
from plcsim.exercise import IO, Exercise
from plcsim.scenario import FAULTS, Scenario, after_event, free_motor, jam_motor

NUMBER = "6.3.5"
MOVES, STROKES = "M1_ZIADANY_POCET", "M2_ZIADANY_POCET"
PER_VISIT = "the required number of punchings at each visit to OS2"
WHOLE = ("two moves, three strokes", "two strokes, then one", "jammed press")

EXERCISE = Exercise(
    number=NUMBER,
    slug="punch-strokes",
    title="Punching machine 5: the required number of press strokes",
    title_sk="Slovné zadanie 5 – Lisovací stroj s dopravníkom",
    task=(
        MODEL + "\n"
        "Task: modify the program of task 4 so that the required number of punchings at each visit to OS2 can be "
        "entered through a parameter of data type INT, M2_ZIADANY_POCET; count the punchings done in "
        "M2_AKTUALNY_POCET (the rising edge of the lower sensor KS2 is one punching) and clear the count when the "
        "object leaves OS2. The object is sent back only after the last punching, with the press at the top again, "
        "and then at once (in the same scan that sees the press back at KS1), as in task 4. As in task 4, the object "
        "makes M1_ZIADANY_POCET moves to OS2 and back, and the moves made so far are kept in M1_AKTUALNY_POCET, 0 "
        "again once the object has been removed. One object at a time, as in task 4; a required count of zero need "
        "not be handled. The operator sets M1_ZIADANY_POCET and M2_ZIADANY_POCET on the HMI before loading an object."
        + " "
        + shuttle_words(reverse_at_os2=False)
        + " "
        + PRESS_WORDS
        + " "
        + PRESS_JAM
    ),
    io=[
        *PUNCH_IO,
        *counts(MOVES, "M1_AKTUALNY_POCET", STROKES, "M2_AKTUALNY_POCET"),
        IO("OBJEKT_PRI_OS2", "the required number of moves is reached", "Bool", "%M0.0", comment="address proposed"),
        IO(
            "OBJEKT_BOL_DOLE",
            "the required number of punchings is done",
            "Bool",
            "%M0.1",
            comment="address proposed",
        ),
        *edge_bits("POM_P_OS1", "POM_N_OS2", "POM_P_OS2", "POM_P_KS2"),
    ],
    rig=Punch,
    scenarios=[
        Scenario(
            "two moves, three strokes",
            *cycles(1, writes={1: {MOVES: 2, STROKES: 3}}),
            duration="38s",
            description="M1_ZIADANY_POCET = 2, M2_ZIADANY_POCET = 3: the object is punched three times at each "
            "of its two visits to OS2",
        ),
        Scenario(
            "two strokes, then one",
            *cycles(2, writes={1: {MOVES: 1, STROKES: 2}, 2: {MOVES: 1, STROKES: 1}}),
            duration="34s",
            description="the first object with two strokes, the second (after the operator has changed the "
            "parameter) with one",
        ),
        Scenario(
            "jammed press",
            *cycles(1, writes={1: {MOVES: 1, STROKES: 2}}),
            jam_motor("M2_DOLE", when=after_event("press stroke"), delay="1.8s..2.2s"),
            free_motor("M2_DOLE", when=after_event("motor jammed"), delay="1.5s..3s"),
            outside={FAULTS: PRESS_JAM},
            duration="22s",
            description="a fault: the press jams on its way down to the second stroke and is freed 1.5..3 s later",
        ),
        Scenario(
            TAKEN_FROM_THE_PRESS,
            *taken_from_the_press({MOVES: 1, STROKES: 3}),
            duration="14s",
            description="M2_ZIADANY_POCET = 3; the operator takes the object from under the press between its first "
            "and second stroke (0.3..1.2 s after the first, while the ram goes back up): no second stroke comes",
        ),
    ],
    checks=[
        *punching_checks(
            parameter(STROKES), product(MOVES, STROKES), "M2_ZIADANY_POCET strokes", (MOVES, STROKES), WHOLE
        ),
        never(all_of("OS2", value("M2_AKTUALNY_POCET") != 0)).named(
            "M2_AKTUALNY_POCET is 0 whenever no object is under the press"
        ),
    ],
    conditions=[assumes("One object at a time", parts_at_once(1))],
    requirements={
        "every stay under the press gets M2_ZIADANY_POCET strokes": PER_VISIT,
        "every stroke comes down on an object": "The press goes down only for an object at OS2",
        "every object is punched M1_ZIADANY_POCET × M2_ZIADANY_POCET times": PER_VISIT,
        "every object is carried to OS2 M1_ZIADANY_POCET times": "the object makes M1_ZIADANY_POCET moves to OS2",
        "the belt reverses within 1 scan once the press is back at KS1 after the last stroke": (
            "and then at once (in the same scan that sees the press back at KS1)"
        ),
        "M2_AKTUALNY_POCET is 0 whenever no object is under the press": "clear the count when the object leaves OS2",
    },
    solutions=[
        solution(
            NUMBER,
            "reference",
            explanation="task 4 with the strokes counted by ADD on the rising edge of KS2 (rung 6), OBJEKT_BOL_DOLE "
            ":= count >= M2_ZIADANY_POCET (rung 7), the count cleared when the object leaves OS2 (rung 8)",
        ),
        solution(
            NUMBER,
            "wrong-count-ks2-level",
            "wrong",
            "(not from the textbook) ADD on the level of KS2: one stroke counts tens of times",
            fails=("every stay under the press gets M2_ZIADANY_POCET strokes",),
        ),
        solution(
            NUMBER,
            "wrong-strokes-greater-than",
            "wrong",
            "(a slip) strokes done as count > required instead of >=: every visit gets one stroke too many",
            fails=("every stay under the press gets M2_ZIADANY_POCET strokes",),
        ),
        solution(
            NUMBER,
            "wrong-no-count-reset",
            "wrong",
            "(not from the textbook) the stroke count is never cleared: later visits get no stroke",
            fails=(
                "every stay under the press gets M2_ZIADANY_POCET strokes",
                "M2_AKTUALNY_POCET is 0 whenever no object is under the press",
            ),
        ),
        solution(
            NUMBER,
            "wrong-repeat-without-object",
            "wrong",
            "(a slip) the next stroke started by the ram coming back up to KS1 (M2_HORE), not by the object at OS2: "
            "the same strokes while the object stays; taken away between two strokes, the press strokes on the "
            "empty place for ever",
            fails=("the press goes down only for an object at OS2", "every stroke comes down on an object"),
        ),
    ],
    spec_equivalent={
        "line 50: t.KS2 → not t.KS2": (
            "P(NOT KS2) counts a stroke as the press leaves KS2, the same stroke a moment later: the spec bounds the "
            "strokes per visit and the count being 0 once the object left OS2 (criteria 1, 2), not that instant"
        ),
        "P(t.KS2, 'POM_P_KS2') → N(t.KS2, 'POM_P_KS2')": (
            "N(KS2) counts a stroke as the press leaves KS2, the same stroke a moment later: the spec bounds the "
            "strokes per visit and the count being 0 once the object left OS2 (criteria 1, 2), not that instant"
        ),
        **COUNT_RUNG_MOVED,
        "OB1: networks bottom and strokes_done swapped": (
            "OBJEKT_BOL_DOLE follows the count a scan later, while the press is still on its way up: the reverse "
            "still comes within 1 scan of KS1 after the last stroke (criterion 2, 6.3.4 criterion 3)"
        ),
        "OB1: network bottom moved to the end": (
            "the count goes up at the end of the scan that sees KS2, so OBJEKT_BOL_DOLE follows a scan later while "
            "the press is on its way up: the strokes and the reverse are the same (criteria 1, 2)"
        ),
        "OB1: networks strokes_done and leaving swapped": (
            "OBJEKT_BOL_DOLE falls in the scan the object leaves OS2 instead of the next, when no stroke can start "
            "(no object at OS2): criteria 1 and 2 are the same"
        ),
    },
    notes=(
        "The textbook names neither stroke count; M2_ZIADANY_POCET and M2_AKTUALNY_POCET are proposed (spec 6.3.5). "
        "Its text cites Figs. 6.44-6.50 but lists eight rungs; the reference has the eight (6.44-6.51). The jam "
        "comes on the way down to the second stroke: the program must neither count a stroke nor move the belt "
        "before the press is back at KS1 after the last one. 'Object taken from under the press' (between the first "
        "and the second stroke) grades what the program must do then, as in 6.3.4: no further stroke, the ram back at "
        "KS1, and M2_AKTUALNY_POCET 0 (the object has left OS2); not the moves and their count "
        "(6.3.4's note). Not a scenario: bouncing KS2. The textbook counts "
        "strokes on P(KS2), and each bounce of the contact is a rising edge, so a bouncing KS2 counts one stroke "
        "several times (the textbook's program is not debounced; 6.3.3 grades the bounce, where only levels are "
        "used)."
    ),
)
