"""4.3.15 Operating-hours meter 2 (hours, minutes, seconds). Plant: CONV1.

The conveyor of 4.3.5 (as in 4.3.14) is graded by keeps_conveyor_control: S1 starts the belt, S2 stops it.

Mutation testing (``plcsim mutate 4.3.15``): the four survivors are the correct programs of 4.3.14,
declared with its reasons (``SPEC_EQUIVALENT`` of ``ex_4_3_14``).
"""

from exercises._common import solution
from exercises._conveyor import CONV1_IO, keeps_conveyor_control
from exercises._hours import (
    counts_running_seconds,
    hms_meter,
    nuluj_resets_itself,
    still_while_off,
    stores_reset_time,
    survives_power_cycle,
    zero_after_reset,
)
from exercises.ex_4_3_14 import FAULT_WORDS, SPEC_EQUIVALENT
from plants import Conv1
from plcsim.check import always, value
from plcsim.exercise import Exercise, only
from plcsim.scenario import FAULTS, Action, Scenario, knock_off, place, power_cycle, write
from plcsim.tags import DB
from plcsim.tags.types import DTL, Bool, UInt, USInt

NUMBER = "4.3.15"
SIGNALS = ("MOTOR.HODINY", "MOTOR.MINUTY", "MOTOR.SEKUNDY")


def earlier_hours(t: str) -> list[Action]:
    """The retentive meter already holds 17 h 43 min 21 s of earlier runs (as an HMI sets it): a reset
    must zero the minutes and hours too, not only the seconds."""
    return [write("MOTOR.HODINY", 17, t=t), write("MOTOR.MINUTY", 43, t=t), write("MOTOR.SEKUNDY", 21, t=t)]


EXERCISE = Exercise(
    number=NUMBER,
    slug="hours-meter-2",
    title="Operating-hours meter 2 (hours, minutes, seconds)",
    title_sk="Príklad 15 – Motohodiny 2",
    task=(
        "Showing operators seconds is not sensible: show hours, minutes and seconds. Modify the data block MOTOR of "
        "4.3.14: SEKUNDY (USInt, seconds 0..59), MINUTY (USInt, minutes 0..59), HODINY (UInt, hours), DATUM_CAS "
        "(DTL, date and time of the last reset) and NULUJ (Bool, triggers the reset).\n"
        "Task: increment SEKUNDY every second while the motor D1 is on. When 60 s are reached, increment MINUTY and "
        "reset SEKUNDY; when MINUTY reaches 60, increment HODINY and reset MINUTY. NULUJ zeroes all three and stores "
        "the date and time as in 4.3.14: write the current date and time to DATUM_CAS and reset NULUJ, in the scan "
        "that reads NULUJ. Over T seconds of running, the meter grows by T +- 1 s; at the end of every scan SEKUNDY "
        "and MINUTY are within 0..59. SEKUNDY, MINUTY, HODINY and DATUM_CAS are retentive, NULUJ is not. Keep the "
        "conveyor control of 4.3.5 (S1 starts the belt, S2 stops it). " + FAULT_WORDS
    ),
    io=CONV1_IO,
    dbs={
        "MOTOR": DB(
            SEKUNDY=USInt(0, retain=True),
            MINUTY=USInt(0, retain=True),
            HODINY=UInt(0, retain=True),
            DATUM_CAS=DTL("DTL#1970-01-01-00:00:00", retain=True),
            NULUJ=Bool(),
        )
    },
    rig=Conv1,
    cpu={"cycle": "100ms", "clock_memory_byte": 0, "system_memory_byte": 1, "rtc_start": "DTL#2026-01-05-08:00:00"},
    record_changes_only=True,
    scenarios=[
        Scenario(
            "two hours",
            *earlier_hours(t="0s"),
            place("p1", at="S1", t="1s..2s"),
            knock_off("p1", t="4s..5s"),
            write("MOTOR.NULUJ", True, t="10s..20s"),
            outside={FAULTS: FAULT_WORDS},
            duration="7350s",
            description="the meter holds 17 h 43 min 21 s from earlier runs; the belt runs empty for about "
            "2 h 2 min after NULUJ (the textbook's example: 7325 s)",
        ),
        Scenario(
            "power cycle",
            place("p1", at="S1", t="1s..2s"),
            knock_off("p1", t="4s..5s"),
            *earlier_hours(t="0s"),
            write("MOTOR.NULUJ", True, t="10s..15s"),
            power_cycle(t="100s..110s"),
            place("p2", at="S1", t="120s..125s"),
            knock_off("p2", t="128s..130s"),
            outside={FAULTS: FAULT_WORDS},
            duration="200s",
            description="the meter passes a minute, the CPU is powered off and on, then the belt runs again",
        ),
    ],
    checks=[
        *keeps_conveyor_control(),
        counts_running_seconds(hms_meter, *SIGNALS),
        always(value("MOTOR.SEKUNDY") <= 59).named("SEKUNDY stays within 0..59 at the end of every scan"),
        always(value("MOTOR.MINUTY") <= 59).named("MINUTY stays within 0..59 at the end of every scan"),
        still_while_off(hms_meter, *SIGNALS),
        zero_after_reset(hms_meter, *SIGNALS),
        nuluj_resets_itself(),
        stores_reset_time(),
        only(survives_power_cycle(hms_meter, *SIGNALS), "power cycle"),
    ],
    requirements={
        "the meter counts the seconds the belt ran": "Over T seconds of running, the meter grows by T +- 1 s",
        "SEKUNDY stays within 0..59 at the end of every scan": (
            "at the end of every scan SEKUNDY and MINUTY are within 0..59"
        ),
        "MINUTY stays within 0..59 at the end of every scan": (
            "at the end of every scan SEKUNDY and MINUTY are within 0..59"
        ),
        "the meter stands still while the belt is off": "increment SEKUNDY every second while the motor D1 is on",
        "NULUJ zeroes the meter in the same scan": "NULUJ zeroes all three",
        "NULUJ resets itself in the same scan": "reset NULUJ, in the scan that reads NULUJ",
        "NULUJ stores the date and time of the reset": "write the current date and time to DATUM_CAS",
        "the meter survives a power cycle (retain)": "SEKUNDY, MINUTY, HODINY and DATUM_CAS are retentive",
    },
    solutions=[
        solution(
            NUMBER,
            "reference",
            explanation="count, then carry seconds into minutes and minutes into hours in "
            "the same scan; NULUJ: MOVE 0 to three outputs, RD_LOC_T",
        ),
        solution(
            NUMBER,
            "wrong-reset-seconds-only",
            "wrong",
            "NULUJ zeroes only SEKUNDY (as in 4.3.14): the minutes and hours of earlier runs survive the reset",
            fails=("NULUJ zeroes the meter in the same scan",),
        ),
        solution(
            NUMBER,
            "wrong-carry-order",
            "wrong",
            "the carry networks run before the counting network, so the meter shows 60 s for one scan",
            fails=("SEKUNDY stays within 0..59 at the end of every scan",),
        ),
    ],
    spec_equivalent=SPEC_EQUIVALENT,
    notes=(
        "The two-hour scenario records a trace row only when a value changes and runs at a 100 ms cycle; the idle "
        "physics of the empty belt is skipped (provably equivalent), so two hours grade in about a second. "
        "HODINY overflow at 65 535 h is not handled by the textbook and is not tested."
    ),
)
