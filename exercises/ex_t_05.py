"""T-05 The daily time switch (the manual's EX-28, FTB on word tables and the real-time clock). Plant: PANEL.

The manual (§7.7, FTB example 3): "Design a time processor for output Y0.0: Y0.0 = 1 daily from 8:00 to 8:45,
8:50 to 9:35, 9:45 to 10:30, 10:50 to 11:35, 11:40 to 12:25, 14:10 to 14:55, 15:05 to 15:50. We use the
registers S7 (minutes) and S8 (hours)." Its listing prints two off-times that contradict the task (gap G13 of
``spec/tecomat.md``): ``$A1D`` is 10:29 and ``$B13`` is 11:19. The task's times are what is graded (``$A1E``,
``$B23``); the listing as printed is shipped as a wrong program that fails exactly there.

The run does not wait for hours: the clock is set (the scenario verb ``set_clock``) half a minute before each
switching time in turn, at a seeded moment inside the interval the output is in, so the output's state is the
same for a program that follows the clock minute by minute and one that compares it with the intervals.
"""

from exercises._tecomat import OnSchedule, il_solution
from plants import Panel
from plcsim.check import always, implies, not_, off
from plcsim.controllers.tecomat.verbs import set_clock
from plcsim.exercise import IO, Exercise
from plcsim.scenario import Scenario

NUMBER = "T-05"
SWITCH_TIMES = "(on at the start of the first minute, off at the start of the last)"
"""What both checks grade, in the task's words."""
ON_TIMES = (0x800, 0x832, 0x92D, 0xA32, 0xB28, 0xE0A, 0xF05)
OFF_TIMES = (0x82D, 0x923, 0xA1E, 0xB23, 0xC19, 0xE37, 0xF32)
"""The task's times as SW7 holds them (hour in the high byte): 08:00 ... 15:05 and 08:45 ... 15:50."""
SCHEDULE = OnSchedule(ON_TIMES, OFF_TIMES)
INSIDE = "vystup is on from each switch-on time to its switch-off time (08:00-08:45 ... 15:05-15:50)"
OUTSIDE = "vystup is off outside those intervals"


def _before(hhmm: int, seconds: int = 30) -> str:
    """``"07:59:30"``: ``seconds`` before the time ``$800``."""
    total = (hhmm >> 8) * 3600 + (hhmm & 0xFF) * 60 - seconds
    return f"{total // 3600:02d}:{total // 60 % 60:02d}:{total % 60:02d}"


def switching_times(extra: tuple[int, ...] = ()) -> list:
    """The clock set half a minute before every switching time of the day in turn (and before the ``extra``
    times, inside an interval), each setting 60..75 s after the previous one (seeded)."""
    moments = sorted((*ON_TIMES, *OFF_TIMES, *extra), key=lambda v: (v >> 8) * 60 + (v & 0xFF))
    actions = [set_clock(_before(moments[0]), t="0s")]
    for k, moment in enumerate(moments[1:], start=1):
        actions.append(set_clock(_before(moment), t=f"{75 * k - 15}s..{75 * k}s"))
    return actions


EXERCISE = Exercise(
    number=NUMBER,
    slug="tecomat-time-switch",
    title="Daily time switch (Tecomat EX-28)",
    title_sk="Tecomat, příklad EX-28 – časový spínač",
    task=(
        "Design a time switch for output vystup (Y0.0): it is on daily from 8:00 to 8:45, 8:50 to 9:35, 9:45 to "
        "10:30, 10:50 to 11:35, 11:40 to 12:25, 14:10 to 14:55 and 15:05 to 15:50 (on at the start of the first "
        "minute, off at the start of the last). Use the real-time clock in S7 (minutes) and S8 (hours), read "
        "together as the word SW7, and two word tables (#table word) searched with FTB. Write it in the Tecomat's "
        "instruction list."
    ),
    io=[IO("vystup", "time-switched output", "Bool", "%Q0.0", comment="Y0.0 as in the manual's EX-28")],
    rig=lambda: Panel(buttons=(), switches=(), lamps=("vystup",)),
    cpu={"cycle": "100ms"},
    dt="100ms",
    scenarios=[
        Scenario(
            "the day's switching times",
            *switching_times(),
            duration="1050s",
            description="the clock set half a minute before each of the 14 switching times in turn",
        ),
        Scenario(
            "misprinted minutes",
            *switching_times(extra=(0xA1D, 0xB13)),
            duration="1200s",
            description="as before, and the clock set to 10:28:30 and 11:18:30 too: the minutes the manual's "
            "listing prints as off-times (10:29 and 11:19) lie inside intervals",
        ),
    ],
    checks=[
        always(implies(SCHEDULE, "vystup")).named(INSIDE),
        always(implies(not_(SCHEDULE), off("vystup"))).named(OUTSIDE),
    ],
    requirements={
        "vystup is on from each switch-on time to its switch-off time (08:00-08:45 ... 15:05-15:50)": SWITCH_TIMES,
        "vystup is off outside those intervals": SWITCH_TIMES,
    },
    solutions=[
        il_solution(NUMBER, "reference", explanation="EX-28 with the task's off-times $A1E (10:30) and $B23 (11:35)"),
        il_solution(
            NUMBER,
            "wrong-printed-constants",
            "wrong",
            "the manual's listing as printed: $A1D is 10:29 and $B13 is 11:19, so the output goes off at 10:29 "
            "and at 11:19, inside the intervals 9:45-10:30 and 10:50-11:35, and stays on at 11:35",
            fails=(INSIDE, OUTSIDE),
        ),
        il_solution(
            NUMBER,
            "wrong-decimal-times",
            "wrong",
            "800 for 8:00 in decimal: SW7 holds 8:00 as $800 (hours in the high byte), so no time is ever found",
            fails=(INSIDE,),
        ),
        il_solution(
            NUMBER,
            "wrong-write-not-set",
            "wrong",
            "WR for SET/RES: the output follows FTB's S1.0 and is on only in the switch-on minute itself",
            fails=(INSIDE,),
        ),
    ],
    notes=(
        "The switching minute counts from the cycle whose turnaround first shows it in S7/S8 (cycle 100 ms); "
        "the check reads the clock at each cycle's start, so it is exact. The clock settings stay inside the "
        "interval the output is in, so a program that keeps the state (SET/RES on the minute, as the manual's) "
        "and one that compares the clock with the intervals are both correct."
    ),
)
