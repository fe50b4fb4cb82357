"""T-01 Motor START/STOP on the Tecomat (the manual's EX-01 and EX-09). Plant: PANEL.

The manual's first example (ch. 3) is a motor started and stopped by two push-buttons, written with a
self-holding contact; EX-09 (§7.2) does the same with SET and RES and says the order matters: the last
instruction wins when both buttons are pressed. Both are correct programs here; the wrong ones are the
slips the two listings are there to prevent.
"""

from exercises._tecomat import both_pressed, il_solution, start_stop
from plants import Panel
from plcsim.check import all_of, always, becomes, holds, implies, off
from plcsim.exercise import IO, Exercise
from plcsim.scenario import Scenario

NUMBER = "T-01"
ON_ALONE = "START alone switches the motor on within 1 cycle"
STOP_WINS = "STOP switches the motor off, also when both are pressed (stop-dominant)"
HOLDS_ON = "releasing START leaves the motor running"
HOLDS_OFF = "releasing STOP leaves the motor stopped"

EXERCISE = Exercise(
    number=NUMBER,
    slug="tecomat-start-stop",
    title="Motor START/STOP (Tecomat EX-01)",
    title_sk="Tecomat, příklad EX-01 – motor START/STOP",
    task=(
        "A motor (contactor output MOTOR, Y0.0) is started by the push-button START (X0.0) and stopped by the "
        "push-button STOP (X0.1); both are normally open (NO) contacts. Write the program in the Tecomat's "
        "instruction list (a .il file).\n"
        "Task: pressing START starts the motor in the cycle that sees it, and it keeps running when START is "
        "released. Pressing STOP stops "
        "it, and it stays stopped when STOP is released. When both buttons are pressed, the motor is stopped "
        "(STOP dominates). A self-holding contact (LD, OR, ANC, WR) or SET and RES may be used."
    ),
    io=[
        IO("START", "start push-button", "Bool", "%I0.0", "NO", comment="X0.0 as in the manual's EX-01"),
        IO("STOP", "stop push-button", "Bool", "%I0.1", "NO", comment="X0.1 as in the manual's EX-01"),
        IO("MOTOR", "motor contactor", "Bool", "%Q0.0", comment="Y0.0 as in the manual's EX-01"),
    ],
    rig=lambda: Panel(buttons=("START", "STOP"), switches=(), lamps=("MOTOR",)),
    scenarios=[
        Scenario(
            "start and stop",
            *start_stop("START", "STOP", 4),
            duration="5s",
            description="START and STOP presses of random length in turn, some repeated",
        ),
        Scenario(
            "both pressed",
            *both_pressed("START", "STOP"),
            duration="5s",
            description="the two buttons pressed together, in either order and in the same instant",
        ),
    ],
    checks=[
        always(implies(all_of("START", off("STOP")), "MOTOR")).named(ON_ALONE),
        always(implies("STOP", off("MOTOR"))).named(STOP_WINS),
        holds("MOTOR").until(becomes("STOP")).named(HOLDS_ON),
        holds(off("MOTOR")).until(becomes(all_of("START", off("STOP")))).named(HOLDS_OFF),
    ],
    requirements={
        "START alone switches the motor on within 1 cycle": "pressing START starts the motor in the cycle that sees it",
        "STOP switches the motor off, also when both are pressed (stop-dominant)": (
            "When both buttons are pressed, the motor is stopped (STOP dominates)"
        ),
        "releasing START leaves the motor running": "it keeps running when START is released",
        "releasing STOP leaves the motor stopped": "it stays stopped when STOP is released",
    },
    solutions=[
        il_solution(NUMBER, "reference", explanation="EX-01: (START OR MOTOR) AND NOT STOP, stop-dominant"),
        il_solution(NUMBER, "set-reset", "alternative", "EX-09: SET then RES; RES last, so STOP wins"),
        il_solution(
            NUMBER,
            "wrong-set-dominant",
            "wrong",
            "RES before SET: the last instruction wins, so with both buttons pressed the motor runs "
            "(set-dominant taken for reset-dominant)",
            fails=(STOP_WINS,),
        ),
        il_solution(
            NUMBER,
            "wrong-start-dominant",
            "wrong",
            "STOP only in the holding branch: START pressed with STOP still starts the motor",
            fails=(STOP_WINS,),
        ),
        il_solution(
            NUMBER,
            "wrong-no-hold",
            "wrong",
            "no holding contact: the motor stops as soon as START is released",
            fails=(HOLDS_ON,),
        ),
        il_solution(
            NUMBER,
            "wrong-stop-and",
            "wrong",
            "AND where ANC was meant: STOP is read as a normally closed contact",
            fails=(ON_ALONE, STOP_WINS),
        ),
    ],
    notes=(
        "'Unchanged when neither button is pressed' is checked as two statements, as in 4.3.4: once on, the "
        "motor runs until a cycle sees STOP; once off, it stays off until a cycle sees START without STOP."
    ),
)
