"""4.3.2 LED control 2 (NC push-button). Plant: PANEL."""

from exercises._common import solution
from exercises._panel import press_pattern
from plants import Panel
from plcsim.check import action, always, count, falls, rises, value
from plcsim.exercise import IO, Exercise, only
from plcsim.scenario import FAULTS, Scenario, press, wire_break

NUMBER = "4.3.2"
FAULT_WORDS = "A broken wire reads as a pressed button (the input is FALSE) and lights the LED"
"""The task's words for its fault scenarios (``Scenario(outside=...)``)."""


EXERCISE = Exercise(
    number=NUMBER,
    slug="led-2",
    title="LED control 2 (NC push-button)",
    title_sk="Príklad 2 – Ovládanie LED",
    task=(
        "As in 4.3.1, the push-button TLACIDLO (push-button) should switch the output LED (lamp), but this time "
        "the button is wired to the input module as a normally closed (NC) contact: the input is TRUE while the "
        "button is NOT pressed and FALSE while it is pressed.\n"
        "Task: while the button is pressed the LED is lit; when the button is released the LED goes out. The LED "
        "follows the button in the scan that reads it, so the lamp lights within 2 scans of a press and goes out "
        "within 2 scans of the release, and every press lights it. A broken wire reads as a pressed button (the "
        "input is FALSE) and lights the LED.\n"
        "(Every solution of 4.3.1 works here once its NO and NC contact instructions are swapped.)"
    ),
    io=[
        IO(
            "TLACIDLO",
            "push-button",
            "Bool",
            "%I0.0",
            "NC",
            comment="wired NC (TRUE while not pressed); address proposed, the textbook gives none",
        ),
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
        Scenario(
            "broken wire",
            *press("TLACIDLO", t="200ms..400ms", hold="50ms..150ms"),
            wire_break("TLACIDLO", t="1s..1.5s"),
            outside={FAULTS: FAULT_WORDS},
            duration="2s",
            description="one press, then the wire of the NC button breaks: the input reads FALSE, as if "
            "the button were pressed for good",
        ),
    ],
    checks=[
        always(value("LED") != value("TLACIDLO")).named("LED is lit exactly while the NC input is FALSE (pressed)"),
        rises("LED").within("2 scans").after(action("press", "TLACIDLO")).named("LED lights within 2 scans of a press"),
        falls("LED")
        .within("2 scans")
        .after(action("release", "TLACIDLO"))
        .named("LED goes out within 2 scans of the release"),
        only(count(rises("LED")).equals(12).named("every press is reproduced on the LED"), "presses"),
        only(
            rises("LED")
            .within("2 scans")
            .after(action("break_wire", "TLACIDLO"))
            .named("a broken wire reads as 'pressed' and lights the LED"),
            "broken wire",
        ),
    ],
    requirements={
        "LED is lit exactly while the NC input is FALSE (pressed)": (
            "The LED follows the button in the scan that reads it"
        ),
        "LED lights within 2 scans of a press": "the lamp lights within 2 scans of a press",
        "LED goes out within 2 scans of the release": "goes out within 2 scans of the release",
        "every press is reproduced on the LED": "every press lights it",
        "a broken wire reads as 'pressed' and lights the LED": (
            "A broken wire reads as a pressed button (the input is FALSE) and lights the LED"
        ),
    },
    solutions=[
        solution(NUMBER, "reference", explanation="NC contact -> coil"),
        solution(NUMBER, "solution-2", "alternative", "NC contact -> SET, NO contact -> RESET"),
        solution(
            NUMBER,
            "wrong-no-contact",
            "wrong",
            "4.3.1's NO contact reused for an NC button: the LED is lit at rest and goes out while pressed",
            fails=("LED is lit exactly while the NC input is FALSE (pressed)", "LED lights within 2 scans of a press"),
        ),
    ],
    notes=(
        "The textbook cites Fig. 4.52 for both the released and the pressed state; the pressed state is Fig. 4.53. "
        "The 'broken wire' scenario shows the consequence of NC wiring the plant section mentions (a broken wire "
        "reads like a pressed button), which is why NC wiring is chosen for STOP-type signals, not for this one. "
        "Acceptance criterion 2 of the catalogue (the same program with the button rewired NO must fail) is a test "
        "of the wiring layer, not of a student program; it is not graded here."
    ),
)
