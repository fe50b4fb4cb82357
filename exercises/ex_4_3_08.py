"""4.3.8 Alarm signalling (blinking LED). Plant: CONV1 with an alarm lamp LED."""

from __future__ import annotations

from exercises._common import solution
from exercises._conveyor import CONV1_IO
from plants import Conv1
from plcsim.check import all_of, durations, duty, falls, never, off, rises
from plcsim.exercise import IO, Exercise, only
from plcsim.scenario import Scenario, after_event, jam, place, write

NUMBER = "4.3.8"

SHORTEST = "0.5s - 1 scan - 1ms"  # spec §2 4.3.8 criterion 2: each phase 0.5 s +- (T_scan + 1 ms)
LONGEST = "0.5s + 1 scan + 1ms"

# The object is placed at 0.499 s, so S1 is seen in the scan at 0.500 s and the 10 s watchdog of 4.3.7 raises
# ALARM in the scan at 10.500 s: on a rising edge of Clock_1Hz, so that the clock-memory solution's first flash is
# a whole one too. The timer solutions then light the LED in [11.001 + k * 1.001, 11.500 + k * 1.001) s.
JAMMED = [
    place("p1", at="S1", t="0.499s"),
    jam("p1", when=after_event("part left", "p1"), delay="0.2s..2s"),
]

EXERCISE = Exercise(
    number=NUMBER,
    slug="alarm-lamp",
    title="Alarm signalling (blinking LED)",
    title_sk="Príklad 8 – Signalizácia alarmu",
    task=(
        "The conveyor of 4.3.5 with the control of 4.3.7 (sensors S1 and S2, normally open; output D1, conveyor "
        "forward; the 10 s transport watchdog sets the memory bit ALARM, which ACK, an HMI button, resets). An "
        "internal memory bit can be shown in a visualisation, but a signal lamp or a siren needs an output.\n"
        "Task: signal the alarm on the output LED (alarm lamp). The LED blinks while ALARM is TRUE, 0.5 s lit and "
        "0.5 s dark, and is dark otherwise. Use the CPU's clock memory (Clock_1Hz, enabled at MB0 in the "
        "hardware configuration) or a timer."
    ),
    io=[
        *CONV1_IO,
        IO("LED", "alarm lamp", "Bool", "%Q0.0", comment="address proposed"),
        IO("ALARM", "transport alarm (4.3.7)", "Bool", "%M10.0", comment="address proposed"),
        IO("ACK", "acknowledge (HMI button)", "Bool", "%M10.1", comment="written by the HMI; address proposed"),
    ],
    rig=lambda: Conv1(lamps=("LED",)),
    cpu={"clock_memory_byte": 0, "system_memory_byte": 1},
    scenarios=[
        Scenario(
            "alarm blinking",
            *JAMMED,
            duration="22s",
            description="the object jams on its way to S2; ALARM is raised at 10.5 s and the LED blinks for 11.5 s",
        ),
        Scenario(
            "alarm acknowledged",
            *JAMMED,
            write("ACK", True, t="21.1s..21.4s"),
            write("ACK", False, t="21.6s..21.9s"),
            duration="23s",
            description="as 'alarm blinking'; the operator acknowledges about 10.6..10.9 s after the alarm, "
            "while the timer solutions' LED is lit",
        ),
    ],
    checks=[
        only(durations("LED").between(SHORTEST, LONGEST).named("each flash lasts 0.5 s"), "alarm blinking"),
        only(
            durations(all_of("ALARM", off("LED")))
            .between(SHORTEST, LONGEST)
            .named("the LED is dark 0.5 s between flashes"),
            "alarm blinking",
        ),
        only(
            duty("LED", start="10.5s", end="20.5s").between(0.48, 0.52).named("duty cycle 50 % +- 2 % over 10 periods"),
            "alarm blinking",
        ),
        never(all_of("LED", off("ALARM"))).for_more_than("1 scan").named("the LED is dark whenever ALARM is FALSE"),
        only(
            falls("ALARM").within("1 scan").after(rises("ACK")).named("ACK clears ALARM within 1 scan"),
            "alarm acknowledged",
        ),
    ],
    solutions=[
        solution(NUMBER, "reference", explanation="LED := ALARM AND Clock_1Hz (clock memory at MB0)"),
        solution(
            NUMBER,
            "solution-2",
            "alternative",
            "TON_B (1 s) restarted by RT; ET <= 500 ms resets the LED, ALARM AND ET > 500 ms sets it",
        ),
        solution(NUMBER, "alternative", "alternative", "TON_B (1 s) restarted by RT; LED := ET > 500 ms"),
        solution(
            NUMBER,
            "wrong-set-reset",
            "wrong",
            "SET/RESET of the LED both conditioned on ALARM: after ACK neither runs and the LED stays lit",
            fails=("the LED is dark whenever ALARM is FALSE",),
        ),
        solution(
            NUMBER,
            "wrong-period",
            "wrong",
            "(from the task's wording, not a textbook solution) 'period 0.5 s' read literally (Clock_2Hz): "
            "0.25 s on, 0.25 s off; the duty cycle is still 50 %",
            fails=("each flash lasts 0.5 s", "the LED is dark 0.5 s between flashes"),
        ),
    ],
    notes=(
        "Text issue: 'period 0.5 s' contradicts '0.5 s TRUE, 0.5 s FALSE'; the exercise uses the half-period 0.5 s "
        "(the parenthesis and the textbook's Clock_1Hz). System memory is at MB1 (the textbook says byte 0 for "
        "both, which TIA does not allow). Solution 2's figure is missing [R]: shipped with the RESET rung "
        "unconditioned by ALARM (correct); the catalogue's reading with ALARM in both rungs is wrong-set-reset. "
        "The alarm is timed to rise on a Clock_1Hz edge so that the clock solution's first flash is a whole one "
        "(criterion 2 speaks of every phase); the acknowledgement falls inside a lit phase of the timer solutions, "
        "so the SET/RESET variant is caught on every seed. Criterion 4 (solution 1's LED edges coincide with "
        "Clock_1Hz edges) holds only for the clock solution and is not graded: checks apply to every solution."
    ),
)
