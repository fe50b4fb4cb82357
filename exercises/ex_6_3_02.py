"""6.3.2 Task 2 — the required number of moves to OS2 (M1_ZIADANY_POCET). Plant: PUNCH."""

from __future__ import annotations

from exercises._common import solution
from exercises._punch import (
    MODEL,
    PUNCH_IO,
    TAKEN_ON_ITS_WAY,
    PerObject,
    arrivals,
    counts,
    counts_arrivals,
    cycles,
    edge_bits,
    interlocks,
    machine_safe,
    parameter,
    shuttle,
    shuttle_words,
    waits_at_os1,
)
from plants import Punch
from plcsim.check import assumes, parts_at_once
from plcsim.exercise import IO, Exercise
from plcsim.scenario import Scenario, after_event, held, place, remove, write

NUMBER = "6.3.2"
REQUIRED = "M1_ZIADANY_POCET"
TAKEN = ("taken",)  # the object the operator takes off the belt on its way to the press

EXERCISE = Exercise(
    number=NUMBER,
    slug="punch-shuttles",
    title="Punching machine 2: the required number of moves",
    title_sk="Slovné zadanie 2 – Lisovací stroj s dopravníkom",
    task=(
        MODEL + "\n"
        "Task: extend the program of task 1 with the parameter M1_ZIADANY_POCET (Int), the required number of moves "
        "of the object to OS2. The object makes the required number of moves (one in task 1) and then waits at OS1 "
        "for its removal; M1_ZIADANY_POCET = 2, for example, means OS1 -> OS2 -> OS1 -> OS2 -> OS1, wait. Keep the "
        "moves made so far in M1_AKTUALNY_POCET (Int), 0 again once the object has been removed, either as the CV "
        "of an up counter CTU or with ADD on the arrivals at OS2. One object at a time; a required count of zero "
        "need not be handled. The operator sets M1_ZIADANY_POCET on the HMI before loading an object."
        + " "
        + shuttle_words()
        + " "
        + TAKEN_ON_ITS_WAY
    ),
    io=[
        *PUNCH_IO,
        *counts(REQUIRED, "M1_AKTUALNY_POCET"),
        IO(
            "OBJEKT_PRI_OS2",
            "the required count is reached (solution 2)",
            "Bool",
            "%M0.0",
            comment="address proposed",
        ),
        *edge_bits("POM_P_OS1", "POM_N_OS2"),
    ],
    rig=Punch,
    scenarios=[
        Scenario(
            "one move, then three",
            *cycles(2, writes={1: {REQUIRED: 1}, 2: {REQUIRED: 3}}),
            duration="44s",
            description="the first object with M1_ZIADANY_POCET = 1; after its removal the operator sets 3 "
            "and loads the second one, which starts a new series",
        ),
        Scenario(
            "two moves",
            *cycles(1, writes={1: {REQUIRED: 2}}),
            duration="22s",
            description="M1_ZIADANY_POCET = 2, one object: OS1 -> OS2 -> OS1 -> OS2 -> OS1, wait",
        ),
        Scenario(
            "object taken on its way",
            write(REQUIRED, 2, t="0.1s"),
            place("taken", at="OS1", t="0.3s..0.8s"),
            remove("taken", when=after_event("part left", "OS1"), delay="0.5s..3.3s"),
            place("p1", at="OS1", when=after_event("part removed", "taken"), delay="1s..2s"),
            remove("p1", when=held("OS1", "1.5s")),
            duration="28s",
            description="a fault: M1_ZIADANY_POCET = 2; the operator takes the first object off the belt on its "
            "first way to OS2 (0.5..3.3 s after it left OS1: no sensor sees it go) and loads the next one at OS1 "
            "1..2 s later, which makes its two moves and waits",
        ),
    ],
    checks=[
        # criterion 1
        PerObject(
            "every object is carried to OS2 M1_ZIADANY_POCET times",
            "arrived at OS2",
            arrivals,
            parameter(REQUIRED),
            reads=(REQUIRED,),
            events=(("part entered", "OS2"),),
            ignore=TAKEN,
        ),
        waits_at_os1(TAKEN),
        # criterion 2
        counts_arrivals(TAKEN),
        # criterion 3
        *shuttle(TAKEN),
        *interlocks(press=False),
        *machine_safe(),
    ],
    conditions=[assumes("One object at a time", parts_at_once(1))],
    requirements={
        "every object is carried to OS2 M1_ZIADANY_POCET times": "The object makes the required number of moves",
    },
    solutions=[
        solution(
            NUMBER,
            "reference",
            explanation="solution 1: CTU_M1 (CU := object at OS2, R := removal edge with the belt standing, PV := "
            "M1_ZIADANY_POCET); its QU blocks the start at OS1; M1_AKTUALNY_POCET := CV",
        ),
        solution(
            NUMBER,
            "solution-2",
            "alternative",
            "solution 2: ADD 1 on the falling edge of OS2; OBJEKT_PRI_OS2 := count >= required; MOVE 0 on the "
            "removal edge with the belt standing",
        ),
        solution(
            NUMBER,
            "wrong-removal-without-motor-test",
            "wrong",
            "solution 2 with the removal edge P(OS1) alone: every departure from OS1 clears the count and the "
            "object shuttles without end (the textbook: the outputs make it a removal with the conveyor standing)",
            fails=(
                "every object is carried to OS2 M1_ZIADANY_POCET times",
                "M1_AKTUALNY_POCET counts the object's arrivals at OS2 and is 0 after its removal",
            ),
        ),
        solution(
            NUMBER,
            "wrong-ctu-reset-without-motor-test",
            "wrong",
            "solution 1 with R := P(OS1) alone: the counter is reset at every departure, QU never comes",
            fails=("every object is carried to OS2 M1_ZIADANY_POCET times",),
        ),
        solution(
            NUMBER,
            "wrong-count-every-scan",
            "wrong",
            "(not from the textbook) ADD without the edge: one arrival counts once per scan",
            fails=(
                "M1_AKTUALNY_POCET counts the object's arrivals at OS2 and is 0 after its removal",
                "every object is carried to OS2 M1_ZIADANY_POCET times",
            ),
        ),
        solution(
            NUMBER,
            "wrong-greater-than",
            "wrong",
            "(not from the textbook) count > required instead of >=: one move too many",
            fails=("every object is carried to OS2 M1_ZIADANY_POCET times",),
        ),
    ],
    notes=(
        "M1_ZIADANY_POCET is written by the scenario before each object is loaded, as an operator sets it on the "
        "HMI (1, 2 and 3 in the scenarios; larger counts only lengthen the run). Both textbook solutions keep "
        "M1_AKTUALNY_POCET (solution 1 stores the CTU's CV, 'for demonstration'), so criterion 2 grades both. The "
        "textbook's wrong removal edge is shipped for both solutions: it shows only with two or more required "
        "moves, when the object sets off from OS1 again after a return. 'Object taken on its way' (6.3.1's fault) "
        "takes the object on its first move, before it has been counted: the belt runs on forward with nothing on "
        "it (no sensor sees the removal), and the next object loaded starts a new series of M1_ZIADANY_POCET "
        "moves. A removal after the first arrival is not a scenario: no program can tell the next object loaded "
        "at OS1 from the object coming back (a removal is seen only at OS1 with the belt standing), so it makes "
        "only the moves left; the task does not say otherwise."
    ),
)
