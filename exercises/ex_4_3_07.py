"""4.3.7 Conveyor alarm (10 s transport watchdog). Plant: CONV1.

Mutation testing (``plcsim mutate 4.3.7``): the two survivors are correct programs, one scan apart from the
reference within the spec's tolerances; ``SPEC_EQUIVALENT`` gives each with the words of the spec that allow it.
"""

from __future__ import annotations

from exercises._common import solution
from exercises._conveyor import CARRY, CONV1_IO, carries_objects, shuttle
from plants import Conv1
from plcsim.check import all_of, always, assumes, count, event, falls, holds, implies, never, off, parts_at_once, rises
from plcsim.exercise import IO, Exercise, GradedCheck, only
from plcsim.scenario import FAULTS, Scenario, after_event, held, jam, knock_off, place, remove, write

NUMBER = "4.3.7"
FAULT_WORDS = "If S2 does not detect the object within the protection time of 10 s"
"""The task's words for its fault scenarios (``Scenario(outside=...)``)."""


ALARM_SCENARIOS = ("jam", "knocked off", "new object during the alarm")


def acknowledge(lo_s: float, hi_s: float) -> list:
    """The operator presses the HMI button ACK between ``lo_s`` and ``hi_s`` (written TRUE, FALSE again
    0.2..0.5 s after ``hi_s``)."""
    return [write("ACK", True, t=f"{lo_s}s..{hi_s}s"), write("ACK", False, t=f"{hi_s + 0.2}s..{hi_s + 0.5}s")]


# p1 is placed at 0.3..0.8 s, so the belt starts by 0.801 s and the watchdog fires by 10.802 s.
JAMMED = [
    place("p1", at="S1", t="0.3s..0.8s"),
    jam("p1", when=after_event("part left", "p1"), delay="0.2s..2s"),
]

THREE_OBJECTS = Scenario(
    "three objects",
    *shuttle(3),
    duration="25s",
    description="normal operation: load at S1, remove at S2 after 1 s, three times (14 s of belt "
    "time in all, so a watchdog that does not restart for each transport gives a false alarm)",
)

NEW_OBJECT_DURING_ALARM = Scenario(
    "new object during the alarm",
    *JAMMED,
    remove("p1", t="12s..12.5s"),
    place("p2", at="S1", t="13.5s..14s"),
    *acknowledge(14.5, 15),
    remove("p2", t="15.6s..15.9s"),
    place("p3", at="S1", t="16.1s..16.4s"),
    remove("p3", when=held("S2", "1s")),
    outside={FAULTS: FAULT_WORDS},
    duration="24s",
    description="after the alarm the operator frees the belt and loads a new object before "
    "acknowledging; the belt must wait for ACK (version 3); after ACK the operator lifts the object and "
    "sets it down on S1 again (a new S1 edge), and the belt carries it to S2",
)


WATCHDOG = (
    "If S2 does not detect the object within the protection time of 10 s, the conveyor stops and an alarm is raised: "
    "the memory bit ALARM (alarm) is set and stays set until the operator acknowledges it with ACK (acknowledge, an "
    "HMI button); ACK clears it in the scan that reads it. While ALARM is TRUE the conveyor stays off; after ACK an "
    "object at S1 starts it again."
)
"""4.3.7's watchdog as its task states it, which :func:`watchdog_checks` grades (4.3.8 keeps it and states it)."""
WATCHDOG_WORDS = {
    "no false alarm in normal operation": "If S2 does not detect the object within the protection time of 10 s",
    "the belt stays off while ALARM is TRUE": "While ALARM is TRUE the conveyor stays off",
}
"""The words of :data:`WATCHDOG` that the checks 4.3.7 and 4.3.8 build themselves grade."""


def watchdog_checks(jams: tuple[str, ...], alarms: tuple[str, ...]) -> list[GradedCheck]:
    """Criteria 2 and 3 of 4.3.7 (also graded in 4.3.8, whose conveyor has "the control of 4.3.7"): in the
    scenarios ``jams`` the belt stops and ALARM rises 10 s after the belt started; in ``alarms`` ALARM latches
    until ACK and ACK clears it within 1 scan."""
    return [
        only(
            falls("D1")
            .between("10s", "10s + 2 scans")
            .after(rises("D1"))
            .named("the belt stops 10 s after it started without reaching S2")
            .grades("If S2 does not detect the object within the protection time of 10 s, the conveyor stops"),
            *jams,
        ),
        only(
            rises("ALARM")
            .between("10s - 1 scan", "10s + 2 scans")
            .after(rises("D1"))
            .named("ALARM is raised 10 s after the belt started")
            .grades("an alarm is raised: the memory bit ALARM (alarm) is set"),
            *jams,
        ),
        only(
            holds("ALARM")
            .until(rises("ACK"))
            .named("ALARM latches until ACK")
            .grades("stays set until the operator acknowledges it with ACK"),
            *alarms,
        ),
        only(
            falls("ALARM")
            .within("1 scan")
            .after(rises("ACK"))
            .named("ACK clears ALARM within 1 scan")
            .grades("ACK clears it in the scan that reads it"),
            *alarms,
        ),
    ]


SPEC_EQUIVALENT = {
    "OB1: networks start_belt and watchdog swapped": (
        "the watchdog sees D1 one scan after it was set, so ALARM comes 10 s + 1 scan after the belt started: "
        "criterion 2 allows [10 s, 10 s + 2 scans]; while an object waits at S1 during the alarm its TON no "
        "longer times (the reference's times a belt that is set and reset in every scan)"
    ),
    "OB1: networks stop_belt and acknowledge swapped": (
        "ACK clears ALARM before the reset rung reads it, so an object waiting at S1 restarts the belt in the "
        "scan that read ACK rather than the next one: criterion 4's 'restarts only after ACK' holds"
    ),
}
"""The mutants of the reference that are correct programs by the spec's words (see plcsim.mutate)."""

EXERCISE = Exercise(
    number=NUMBER,
    slug="conveyor-alarm",
    title="Conveyor alarm (10 s transport watchdog)",
    title_sk="Príklad 7 – Alarm dopravníka",
    task=(
        "The conveyor of 4.3.5: sensors S1 (belt start) and S2 (belt end), both normally open, output D1 "
        "(conveyor forward). With the program of 4.3.5 the belt would run forever if the object fell off or "
        "jammed.\n"
        "Task: an object loaded at the beginning is detected by S1. "
        + CARRY
        + ". One object at a time. "
        + WATCHDOG
        + " "
        "(textbook version 3)."
    ),
    io=[
        *CONV1_IO,
        IO("ALARM", "transport alarm", "Bool", "%M10.0", comment="internal memory bit (4.3.8); address proposed"),
        IO("ACK", "acknowledge (HMI button)", "Bool", "%M10.1", comment="written by the HMI; address proposed"),
    ],
    rig=Conv1,
    scenarios=[
        THREE_OBJECTS,
        Scenario(
            "jam",
            *JAMMED,
            *acknowledge(13, 14),
            outside={FAULTS: FAULT_WORDS},
            duration="16s",
            description="the object jams 0.2..2 s after leaving S1; the belt slips under it; the operator "
            "acknowledges the alarm 2..3.7 s after it was raised",
        ),
        Scenario(
            "knocked off",
            place("p1", at="S1", t="0.3s..0.8s"),
            knock_off("p1", when=after_event("part left", "p1"), delay="1s..3s"),
            *acknowledge(12.5, 13.5),
            outside={FAULTS: FAULT_WORDS},
            duration="15s",
            description="the object is pushed off the side of the belt on its way to S2",
        ),
        NEW_OBJECT_DURING_ALARM,
    ],
    checks=[
        # normal operation (criteria 1 and 5)
        only(never("ALARM").named("no false alarm in normal operation"), "three objects"),
        *(only(check, "three objects") for check in carries_objects(3)),
        # the watchdog (criterion 2)
        *watchdog_checks(("jam", "knocked off"), ALARM_SCENARIOS),
        # version 3 blocks the belt (criterion 4)
        only(
            always(implies("ALARM", off("D1"))).named("the belt stays off while ALARM is TRUE"),
            "new object during the alarm",
        ),
        # Spec §2 4.3.7 criterion 4: "Version 3: D1 stays FALSE while ALARM is TRUE, restarts only after ACK and a
        # new S1 edge." The scenario gives the new S1 edge after ACK (the object set down on S1 again), so a program
        # whose belt starts on the edge of S1 passes, and so does one that restarts on the level of S1 at ACK.
        only(
            count(event("part entered", "S2")).equals(1).named("after ACK the waiting object is carried to S2"),
            "new object during the alarm",
        ),
        only(
            never(all_of("D1", "S2")).named("the belt never runs while S2 sees an object"),
            "three objects",
            "new object during the alarm",
        ),
        only(
            never(event("part fell off")).named("no object falls off the belt"),
            "three objects",
            "jam",
            "new object during the alarm",
        ),
    ],
    conditions=[assumes("One object at a time", parts_at_once(1))],
    requirements={
        **WATCHDOG_WORDS,
        "after ACK the waiting object is carried to S2": "after ACK an object at S1 starts it again",
        "the belt never runs while S2 sees an object": "so that the object stays on the belt at S2",
        "no object falls off the belt": "so that the object stays on the belt at S2",
    },
    solutions=[
        solution(
            NUMBER,
            "reference",
            explanation="version 3: the watchdog's Q sets ALARM; S2, Q or ALARM reset D1; ACK resets ALARM",
        ),
        solution(
            NUMBER,
            "version-2",
            "alternative",
            "version 2: the alarm only indicates; a new object restarts the belt even while ALARM is TRUE",
            scenarios=("three objects", "jam", "knocked off"),
        ),
        solution(
            NUMBER,
            "version-1",
            "wrong",
            "version 1: nothing resets ALARM (no acknowledgement yet)",
            fails=("ACK clears ALARM within 1 scan",),
        ),
        solution(
            NUMBER,
            "wrong-scan-order",
            "wrong",
            "(catalogue analysis of the missing figure) the reset rung reads TON_A.Q before the TON box runs: "
            "the read refreshes the timer, D1 is reset, the box then sees IN = FALSE and ALARM is never set",
            fails=("ALARM latches until ACK", "ALARM is raised 10 s after the belt started"),
        ),
        solution(
            NUMBER,
            "wrong-alarm-coil",
            "wrong",
            "ALARM := TON_A.Q is TRUE for one scan only: the alarm does not latch",
            fails=("ALARM latches until ACK",),
        ),
    ],
    spec_equivalent=SPEC_EQUIVALENT,
    notes=(
        "Reference = version 3 (the task's 'the conveyor stops and an alarm is raised' plus criterion 4's "
        "blocking); version 2 is graded on every scenario but 'new object during the alarm', where by design it "
        "restarts the belt. The rung order of versions 2 and 3 is a reconstruction [R]: the TON box runs before "
        "the reset rung reads TON_A.Q; the textbook's drawing order, if the reset rung came first, is the "
        "scan-order trap (wrong-scan-order) under the S7-1200 timer-refresh rule. ALARM is a memory bit, which "
        "the trace stamps at the start of the scan that set it, while D1 (an output) is stamped at the end of its "
        "scan: hence '10s - 1 scan' as the lower bound for ALARM. In the 'new object during the alarm' scenario "
        "the new object waits at S1, so version 3's level-sensitive S1 rung restarts the belt in the scan after "
        "ACK (criterion 4's 'new S1 edge' has then already happened while ALARM was TRUE); the operator then lifts "
        "the object and sets it down on S1 again, the new S1 edge after ACK that a program starting the belt on "
        "the rising edge of S1 waits for: both readings of criterion 4 carry it to S2. In version 3 the waiting "
        "object's S1 sets D1 in every scan and the watchdog rung, between the set and the reset, sees D1 TRUE: "
        "TON_A times from the placement of the waiting object, so the scenario acknowledges and sets the object "
        "down again soon enough that it reaches S2 within those 10 s (by 21.5 s; the earliest placement is at "
        "13.5 s)."
    ),
)
