"""4.3.14 Operating-hours meter 1 (seconds). Plant: CONV1 (the motor is the conveyor drive D1).

The task keeps "the conveyor control of 4.3.5 (S1 starts the belt, S2 stops it)": keeps_conveyor_control
grades it, so a meter that counts a belt which never starts or never stops no longer passes.

Mutation testing (``plcsim mutate 4.3.14``): the four survivors are correct programs and are not killed on
purpose; ``SPEC_EQUIVALENT`` gives each with the words of the spec that allow it.
"""

from exercises._common import solution
from exercises._conveyor import CONV1_IO, keeps_conveyor_control
from exercises._hours import (
    counts_running_seconds,
    nuluj_resets_itself,
    resets_in_every_phase,
    seconds_meter,
    still_while_off,
    stores_reset_time,
    survives_power_cycle,
    zero_after_reset,
)
from plants import Conv1
from plcsim.exercise import Exercise, only
from plcsim.scenario import FAULTS, Scenario, held, knock_off, place, power_cycle, remove, write
from plcsim.tags import DB
from plcsim.tags.types import DTL, Bool, DInt

NUMBER = "4.3.14"
FAULT_WORDS = (
    "An object knocked off the belt on its way leaves the belt running (the control of 4.3.5 stops it only at S2), "
    "and that running time is counted like any other."
)
"""The task's words for the object its scenarios knock off, so that the belt runs long (4.3.15 states them too)."""
METER = "MOTOR.SEKUNDY"

_PULSE_A_SCAN_LATER = "the count uses the pulse one scan later, still once a second (criterion 1: T +- 1 in T s)"
SPEC_EQUIVALENT = {
    "P(t.Clock_1Hz, 'TAKT_SB') → N(t.Clock_1Hz, 'TAKT_SB')": (
        "the falling edge of Clock_1Hz is a 1 s pulse too (as in 4.3.11): criterion 1 ('increases by exactly 1 on "
        "each Takt1s pulse ... over T seconds the increase is T +- 1') holds for it"
    ),
    "OB1: networks takt and count_seconds swapped": _PULSE_A_SCAN_LATER,
    "OB1: network takt moved to the end": _PULSE_A_SCAN_LATER,
    "OB1: network start_belt moved to the end": (
        "the counting network reads D1 one scan later when the belt starts: a pulse in that one scan is not "
        "counted, which criterion 1's T +- 1 allows"
    ),
}
"""The mutants of the reference that are correct programs by the spec's words (see plcsim.mutate);
4.3.15's reference has the same networks and the same four."""

EXERCISE = Exercise(
    number=NUMBER,
    slug="hours-meter-1",
    title="Operating-hours meter 1 (seconds)",
    title_sk="Príklad 14 – Motohodiny 1",
    task=(
        "The conveyor of 4.3.5 is driven by output D1 (conveyor forward) at %Q0.2. The goal is not a new conveyor "
        "algorithm but new variables for monitoring: an operating-hours meter (motohodiny) of the motor.\n"
        "Task: create a data block MOTOR with SEKUNDY (DInt, running time in seconds), DATUM_CAS (DTL, date and "
        "time of the last reset) and NULUJ (Bool, 'zero it': triggers the reset). Increment SEKUNDY every second "
        "while the motor is on. When NULUJ becomes TRUE, set SEKUNDY to zero, write the current date and time to "
        "DATUM_CAS and reset NULUJ. SEKUNDY and DATUM_CAS are retentive, NULUJ is not. Keep the conveyor control "
        "of 4.3.5 (S1 starts the belt, S2 stops it). "
        + FAULT_WORDS
        + " Over T seconds of running, SEKUNDY grows by T +- 1. NULUJ "
        "takes effect, and is reset, in the scan that reads it."
    ),
    io=CONV1_IO,
    dbs={
        "MOTOR": DB(SEKUNDY=DInt(0, retain=True), DATUM_CAS=DTL("DTL#1970-01-01-00:00:00", retain=True), NULUJ=Bool())
    },
    rig=Conv1,
    cpu={"cycle": "100ms", "clock_memory_byte": 0, "system_memory_byte": 1, "rtc_start": "DTL#2026-01-05-08:00:00"},
    scenarios=[
        Scenario(
            "belt runs",
            place("p1", at="S1", t="1s..2s"),
            knock_off("p1", t="4s..5s"),
            *resets_in_every_phase("30s"),
            place("p2", at="S1", t="80s..85s"),
            remove("p2", when=held("S2", "1s")),
            outside={FAULTS: FAULT_WORDS},
            duration="125s",
            description="the first object is knocked off, so the belt runs empty; NULUJ ten times from 30 s, "
            "one of them read by the scan of the 1 s pulse; a second object stops the belt at S2 at about "
            "85..90 s and the belt stays off",
        ),
        Scenario(
            "power cycle",
            place("p1", at="S1", t="1s..2s"),
            knock_off("p1", t="4s..5s"),
            write("MOTOR.NULUJ", True, t="10s..15s"),
            power_cycle(t="40s..50s"),
            place("p2", at="S1", t="60s..65s"),
            knock_off("p2", t="68s..70s"),
            outside={FAULTS: FAULT_WORDS},
            duration="100s",
            description="the meter runs, the CPU is powered off and on (the belt stops: D1 is not retentive), "
            "then the belt runs again",
        ),
    ],
    checks=[
        *keeps_conveyor_control(),
        counts_running_seconds(seconds_meter, METER),
        still_while_off(seconds_meter, METER),
        zero_after_reset(seconds_meter, METER),
        nuluj_resets_itself(),
        stores_reset_time(),
        only(survives_power_cycle(seconds_meter, METER), "power cycle"),
    ],
    requirements={
        "the meter counts the seconds the belt ran": "Over T seconds of running, SEKUNDY grows by T +- 1",
        "the meter stands still while the belt is off": "Increment SEKUNDY every second while the motor is on",
        "NULUJ zeroes the meter in the same scan": "NULUJ takes effect, and is reset, in the scan that reads it",
        "NULUJ resets itself in the same scan": "NULUJ takes effect, and is reset, in the scan that reads it",
        "NULUJ stores the date and time of the reset": "write the current date and time to DATUM_CAS",
        "the meter survives a power cycle (retain)": "SEKUNDY and DATUM_CAS are retentive",
    },
    solutions=[
        solution(
            NUMBER, "reference", explanation="Takt1s = P(Clock_1Hz); ADD while D1; NULUJ: MOVE 0, RD_LOC_T, R NULUJ"
        ),
        solution(
            NUMBER,
            "wrong-no-edge",
            "wrong",
            "Clock_1Hz used as a level: the ADD runs in every scan of the half second",
            fails=("the meter counts the seconds the belt ran",),
        ),
        solution(
            NUMBER,
            "wrong-reset-first",
            "wrong",
            "the reset network comes before the counting network: a reset read in the scan of the 1 s pulse "
            "leaves SEKUNDY at 1",
            fails=("NULUJ zeroes the meter in the same scan",),
        ),
        solution(
            NUMBER,
            "wrong-not-retentive",
            "wrong",
            "the count lives in a non-retentive tag: a power cycle loses it",
            fails=("the meter survives a power cycle (retain)",),
        ),
    ],
    spec_equivalent=SPEC_EQUIVALENT,
    notes=(
        "Runs at a 100 ms cycle (the textbook allows cycles up to 100 ms) so that minutes of running grade in a "
        "fraction of a second; while the belt runs empty the plant is quiescent and the simulator skips its idle "
        "physics steps (provably equivalent: see plcsim.sim.Simulation._skip_quiet). The DTL uses the real layout "
        "(MONTH..SECOND USInt; Fig. 4.125 shows UInt, an erratum). Clock memory at MB0, system memory at MB1 "
        "(the textbook's 'byte 0 for both' is an erratum)."
    ),
)
