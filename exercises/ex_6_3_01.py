"""6.3.1 Task 1 — shuttle OS1 -> OS2 -> OS1. Plant: PUNCH."""

from __future__ import annotations

from exercises._common import solution
from exercises._punch import (
    MODEL,
    PUNCH_IO,
    TAKEN_ON_ITS_WAY,
    WAITS,
    PerObject,
    arrivals,
    constant,
    cycles,
    edge_bits,
    interlocks,
    machine_safe,
    removed,
    shuttle,
    shuttle_words,
)
from plants import Punch
from plcsim.check import assumes, count, parts_at_once, rises
from plcsim.exercise import IO, Exercise, only
from plcsim.scenario import Scenario, after_event, held, place, remove

NUMBER = "6.3.1"
CARRIED = "carries an object loaded in front of OS1 to the end of the conveyor at OS2 and then returns it"

TAKEN = ("taken",)  # the object the operator takes off the belt on its way to the press
OBJECTS = 3

EXERCISE = Exercise(
    number=NUMBER,
    slug="punch-shuttle",
    title="Punching machine 1: shuttle OS1 -> OS2 -> OS1",
    title_sk="Slovné zadanie 1 – Lisovací stroj s dopravníkom",
    task=(
        MODEL + "\n"
        "Task: create a program that carries an object loaded in front of OS1 to the end of the conveyor at OS2 and "
        "then returns it to the loading place at OS1. There the conveyor stops and waits for the object to be "
        "removed. After the removal a new object can be loaded. Consider one object at a time. Remember that the "
        "object has been at OS2 in the bit OBJEKT_PRI_OS2; the removal is the object leaving OS1 while the conveyor "
        "stands (edge memory bit POM_P_OS1)." + " " + shuttle_words() + " " + TAKEN_ON_ITS_WAY
    ),
    io=[
        *PUNCH_IO,
        IO("OBJEKT_PRI_OS2", "the object has been at OS2", "Bool", "%M0.0", comment="address proposed"),
        *edge_bits("POM_P_OS1"),
    ],
    rig=Punch,
    scenarios=[
        Scenario(
            "three objects",
            *cycles(OBJECTS),
            duration="42s",
            description="three objects, one after the other: each is loaded at OS1, carried to OS2 and back, and "
            "taken away after resting 1.5..2 s at OS1; the next is loaded 1..2 s after the removal",
        ),
        Scenario(
            "object taken on its way",
            place("taken", at="OS1", t="0.3s..0.8s"),
            remove("taken", when=after_event("part left", "OS1"), delay="0.5s..2.5s"),
            place("p1", at="OS1", when=after_event("part removed", "taken"), delay="1s..2s"),
            remove("p1", when=held("OS1", "1.5s")),
            duration="22s",
            description="a fault: the operator takes the first object off the belt on its way to OS2 (the belt "
            "runs on forward with nothing on it); the next object loaded at OS1 is carried to OS2 and back",
        ),
    ],
    checks=[
        # criterion 1
        *shuttle(TAKEN),
        # criterion 2
        *interlocks(press=False),
        # criteria 3 and 4
        only(
            PerObject(
                "every object is carried to OS2 exactly once", "arrived at OS2", arrivals, constant(1), ignore=TAKEN
            ),
            "three objects",
            "object taken on its way",
        ),
        only(
            PerObject(
                "every object waits at OS1 until it is taken away",
                "was taken away at OS1",
                removed,
                constant(1),
                ignore=TAKEN,
            ),
            "three objects",
            "object taken on its way",
        ),
        only(
            count(rises("M1_VPRED")).equals(OBJECTS).named("the belt starts forward once per object"),
            "three objects",
        ),
        *machine_safe(),
    ],
    conditions=[assumes("Consider one object at a time", parts_at_once(1))],
    requirements={
        "every object is carried to OS2 exactly once": CARRIED,
        "every object waits at OS1 until it is taken away": WAITS,
        "the belt starts forward once per object": CARRIED,
    },
    solutions=[
        solution(
            NUMBER,
            "reference",
            explanation="S M1_VPRED at OS1 unless OBJEKT_PRI_OS2 (upper branch), R M1_VZAD at OS1 (lower); at OS2 "
            "reverse and S OBJEKT_PRI_OS2; removal = rising edge of OS1 with the belt standing",
        ),
        solution(
            NUMBER,
            "wrong-helper-bit-in-both-branches",
            "wrong",
            "OBJEKT_PRI_OS2 in front of both branches: the returning object does not stop the belt at OS1 and "
            "falls off the loading end (the textbook: the bit is only in the upper branch because there the "
            "detection must stop the motion)",
            fails=("the returning object stops at OS1 within 1 scan", "no object falls off the belt"),
        ),
        solution(
            NUMBER,
            "wrong-forward-coil",
            "wrong",
            "(not from the textbook) M1_VPRED as a coil: the belt runs only while OS1 sees the object",
            fails=("every object is carried to OS2 exactly once",),
        ),
        solution(
            NUMBER,
            "wrong-forward-not-reset",
            "wrong",
            "(not from the textbook) at OS2 M1_VZAD is set but M1_VPRED not reset: both directions at once",
            fails=("the belt is never driven forward and backward at once",),
        ),
        solution(
            NUMBER,
            "wrong-nc-as-no",
            "wrong",
            "(not from the textbook) the NC barriers read as NO: the empty belt runs backward from the start",
            fails=("every object is carried to OS2 exactly once",),
        ),
    ],
    notes=(
        "All eight signals of the model are wired, KS1/KS2 and the press motor too: the press waits at the top and a "
        "program of this task leaves it alone (criterion: the press is never driven against an end stop). The "
        "removal edge needs the belt-standing test only from 6.3.2 on (here the object leaving OS1 at the start "
        "resets a bit that is not yet set), so a program without it is correct. 'Object taken on its way' is a "
        "fault: the belt runs on forward with nothing on it until the next object is loaded, which the textbook's "
        "program then serves normally. Not a scenario: a flickering OS1. The removal edge P(OS1) with the belt "
        "standing takes a flicker of the returning object's beam for a removal and sets off again (the textbook's "
        "program is not debounced)."
    ),
)
