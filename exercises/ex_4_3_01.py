"""4.3.1 LED control 1 (NO push-button). Plant: PANEL."""

from exercises._common import solution
from exercises._panel import press_pattern
from plants import Panel
from plcsim.check import action, always, count, rises, same
from plcsim.exercise import IO, Exercise
from plcsim.scenario import Scenario

NUMBER = "4.3.1"


EXERCISE = Exercise(
    number=NUMBER,
    slug="led-1",
    title="LED control 1 (NO push-button)",
    title_sk="Príklad 1 – Ovládanie LED",
    task=(
        "A digital input should switch a digital output on. The push-button TLACIDLO (push-button) is wired to "
        "the input module as a normally open (NO) contact; the output LED (lamp) lights a lamp.\n"
        "Task: while the button is pressed the LED is lit; when the button is released the LED goes out. The LED "
        "follows the button in the scan that reads it, so the lamp lights within 2 scans of a press, and every "
        "press lights it."
    ),
    io=[
        IO("TLACIDLO", "push-button", "Bool", "%I0.0", "NO", comment="address proposed; the textbook gives none"),
        IO("LED", "lamp", "Bool", "%Q0.0", comment="address proposed"),
    ],
    rig=lambda: Panel(buttons=("TLACIDLO",), switches=(), lamps=("LED",)),
    scenarios=[
        Scenario(
            "presses",
            *press_pattern("TLACIDLO"),
            duration="4s",
            description="12 presses of random length (2..150 ms) at seeded times",
        ),
    ],
    checks=[
        always(same("LED", "TLACIDLO")).named("LED equals the button in every scan"),
        rises("LED").within("2 scans").after(action("press", "TLACIDLO")).named("LED lights within 2 scans"),
        count(rises("LED")).equals(12).named("every press is reproduced on the LED"),
    ],
    requirements={
        "LED equals the button in every scan": "The LED follows the button in the scan that reads it",
        "LED lights within 2 scans": "the lamp lights within 2 scans of a press",
        "every press is reproduced on the LED": "every press lights it",
    },
    solutions=[
        solution(NUMBER, "reference", explanation="NO contact -> coil"),
        solution(NUMBER, "solution-2", "alternative", "NC contact -> negated coil"),
        solution(NUMBER, "solution-3", "alternative", "SET while pressed, RESET while released"),
        solution(
            NUMBER,
            "wrong-latch",
            "wrong",
            "SET without RESET: the LED never goes out",
            fails=("LED equals the button in every scan",),
        ),
    ],
)
