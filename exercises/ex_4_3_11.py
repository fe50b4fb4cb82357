"""4.3.11 1-second clock pulse ("Takt 1s"). Plant: none (a PLC-only run).

Mutation testing (``plcsim mutate 4.3.11``): the reference has two mutants. The edge removed
(Takt1s := Clock_1Hz) is killed; ``P -> N`` is a correct program (``spec_equivalent`` says why).
"""

from exercises._common import solution
from plcsim.check import count, durations, rises, spacing
from plcsim.exercise import IO, Exercise, only
from plcsim.scenario import Scenario

NUMBER = "4.3.11"
FAST, SLOW = "1 ms cycle", "100 ms cycle"

EXERCISE = Exercise(
    number=NUMBER,
    slug="takt-1s",
    title='1-second clock pulse ("Takt 1s")',
    title_sk="Príklad 11 – Takt 1s",
    task=(
        "4.3.8 showed two ways to make a signal that toggles with a given frequency. In practice the rising edge "
        "of such a signal is often used: with the given frequency a variable becomes TRUE (otherwise it is FALSE), "
        "and can be used e.g. to increment a variable.\n"
        "Task: create a memory bit Takt1s (1-second pulse) that becomes TRUE every second, for one scan, and is "
        "FALSE the rest of the time. The program runs with a 1 ms and with a 100 ms cycle; a pulse may come at most 2 "
        "scans late at the 1 ms cycle and at most 1 scan late at the 100 ms cycle.\n"
        "The CPU has clock memory enabled at MB0 (Clock_1Hz = %M0.5, toggling every 0.5 s) and system memory at "
        "MB1 (AlwaysTRUE = %M1.2). Timers are IEC_TIMER instances declared in your program."
    ),
    io=[
        IO(
            "Takt1s",
            "1-second pulse, TRUE for one scan each second",
            "Bool",
            "%M10.2",
            comment="memory bit; address proposed",
        ),
    ],
    rig=None,
    cpu={"clock_memory_byte": 0, "system_memory_byte": 1, "cycle": "1ms"},
    scenario_cpu={SLOW: {"cycle": "100ms"}},
    scenarios=[
        Scenario(FAST, duration="60s", description="60 s at the usual 1 ms OB1 cycle"),
        Scenario(SLOW, duration="12s", description="12 s with a slow OB1 cycle of 100 ms"),
    ],
    checks=[
        durations("Takt1s").equals("1 scan").named("Takt1s is TRUE for exactly one scan at a time"),
        only(
            count(rises("Takt1s")).between(59, 61).named("Takt1s pulses once a second (60 +- 1 pulses in 60 s)"), FAST
        ),
        only(
            spacing(rises("Takt1s"))
            .between("1s", "1s + 2 scans")
            .named("at a 1 ms cycle the pulses come every 1 s (+ at most 2 scans)"),
            FAST,
        ),
        only(
            spacing(rises("Takt1s"))
            .between("1s", "1s + 1 scan")
            .named("at a 100 ms cycle the pulses come every 1 s (+ at most 1 scan)"),
            SLOW,
        ),
    ],
    requirements={
        "Takt1s is TRUE for exactly one scan at a time": "for one scan, and is FALSE the rest of the time",
        "Takt1s pulses once a second (60 +- 1 pulses in 60 s)": "becomes TRUE every second",
        "at a 1 ms cycle the pulses come every 1 s (+ at most 2 scans)": "at most 2 scans late at the 1 ms cycle",
        "at a 100 ms cycle the pulses come every 1 s (+ at most 1 scan)": "at most 1 scan late at the 100 ms cycle",
    },
    solutions=[
        solution(NUMBER, "reference", explanation="solution 1: rising edge of Clock_1Hz, exactly every 1.000 s"),
        solution(
            NUMBER,
            "solution-2",
            "alternative",
            "solution 2: TON on AlwaysTRUE reset by RT in its expiry scan, every 1 s + 1 scan",
        ),
        solution(
            NUMBER,
            "wrong-3",
            "wrong",
            "solution 3, 'not quite correct': IN = NOT Takt1s costs one more scan per period (1 s + 2 scans); "
            "fine at 1 ms, but at a 100 ms cycle the clock is off by up to 10 %",
            fails=("at a 100 ms cycle the pulses come every 1 s (+ at most 1 scan)",),
        ),
        solution(
            NUMBER,
            "wrong-4",
            "wrong",
            "solution 4, wrong: the NC contact on TON_T.Q refreshes the instance before the box runs, so in "
            "the expiry scan IN is FALSE and the timer resets itself; Takt1s is never TRUE",
            fails=(
                "Takt1s pulses once a second (60 +- 1 pulses in 60 s)",
                "at a 1 ms cycle the pulses come every 1 s (+ at most 2 scans)",
            ),
        ),
    ],
    spec_equivalent={
        "P(t.Clock_1Hz, 'AUX') → N(t.Clock_1Hz, 'AUX')": (
            "the falling edge of Clock_1Hz is a one-scan pulse every 1.000 s too, half a second later: the task "
            "asks for a variable 'TRUE every second' for one scan, not in phase with the rising edge (a check on "
            "the phase would fail the textbook's solution 2, a self-restarting TON in no phase with the clock)"
        ),
    },
    notes=(
        "Solution 3 ('not quite correct' in the textbook) is shipped as a wrong solution: it passes at a 1 ms "
        "cycle and fails only the 100 ms scenario, where its period is 1.2 s against solution 2's 1.1 s (the "
        "textbook's 'up to 10 %'). Solution 4 fails because the CPU runs the s7_1200 timer dialect (Q/ET refresh "
        "when read); under the 'iec' dialect it would pulse like solution 2 (tests/course/test_takt.py shows both). "
        "The exercise has no operator, so its scenarios have no seeded times. The edge memory bit of solution 1 "
        "is not named in the textbook; %M10.3 is proposed."
    ),
)
