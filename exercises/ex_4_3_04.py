"""4.3.4 LED on/off without SET and RESET. Plant: PANEL."""

from exercises._common import solution
from plants import Panel
from plcsim.check import all_of, always, becomes, holds, implies, off, program_uses_no
from plcsim.exercise import IO, Exercise
from plcsim.scenario import Scenario, press

NUMBER = "4.3.4"
ZAP, VYP = "TLACIDLO_ZAP", "TLACIDLO_VYP"


def on_off(cycles: int) -> list:
    """Alternate ON and OFF presses (2..150 ms) at seeded times; every other cycle presses a button twice
    (ON while already on, OFF while already off)."""
    actions: list = []
    t = 200
    for k in range(cycles):
        for button in (ZAP, VYP):
            repeats = 2 if k % 2 else 1
            for _ in range(repeats):
                actions += press(button, t=f"{t}ms..{t + 80}ms", hold="2ms..150ms")
                t += 300
    return actions


def both_pressed() -> list:
    """The overlaps: ON held, OFF pressed and released while ON is still held; then OFF held first,
    ON pressed during it and still held when OFF is released; then a plain OFF; at the end both are
    pressed in the same instant."""
    return [
        *press(ZAP, t="200ms..300ms", hold="1.2s..1.4s"),  # ON ... (held until 1.4..1.7 s)
        *press(VYP, t="600ms..700ms", hold="300ms..500ms"),  # ... OFF pressed and released inside it
        *press(VYP, t="2s..2.1s", hold="600ms..800ms"),  # OFF held first (until 2.6..2.9 s)
        *press(ZAP, t="2.3s..2.4s", hold="900ms..1.1s"),  # ON pressed inside it, still held after it
        *press(VYP, t="3.8s..3.9s", hold="50ms..150ms"),  # a plain OFF at the end
        *press(ZAP, t="4.2s..4.3s", hold="50ms..100ms"),  # ON pressed and released, then OFF pressed
        *press(VYP, t="4.33s..4.36s", hold="200ms..300ms"),  # and ON pressed again while OFF is held
        *press(ZAP, t="4.45s..4.5s", hold="20ms..50ms"),
        *press(ZAP, t="5.2s", hold="300ms..400ms"),  # both pressed in the same instant,
        *press(VYP, t="5.2s", hold="100ms..200ms"),  # OFF released first: the LED comes on
    ]


EXERCISE = Exercise(
    number=NUMBER,
    slug="led-on-off",
    title="LED on/off without SET and RESET",
    title_sk="Príklad 4 – Ovládanie LED bez SET a RESET",
    task=(
        "Two push-buttons, TLACIDLO_ZAP (ON button) and TLACIDLO_VYP (OFF button), are wired as normally open "
        "(NO) contacts; the output LED (lamp) lights a lamp.\n"
        "Task: pressing TLACIDLO_ZAP switches the LED on, in the scan that sees it; releasing it does not affect the "
        "LED (it stays lit). "
        "Pressing TLACIDLO_VYP switches the LED off; releasing it does not affect the LED. When both buttons "
        "are pressed, the output is off. Implement the program without SET and RESET."
    ),
    io=[
        IO(ZAP, "ON button", "Bool", "%I0.0", "NO", comment="address proposed; the textbook gives none"),
        IO(VYP, "OFF button", "Bool", "%I0.1", "NO", comment="address proposed"),
        IO("LED", "lamp", "Bool", "%Q0.0", comment="address proposed"),
    ],
    rig=lambda: Panel(buttons=(ZAP, VYP), switches=(), lamps=("LED",)),
    scenarios=[
        Scenario(
            "on and off",
            *on_off(4),
            duration="5s",
            description="ON and OFF presses of random length in turn, some repeated",
        ),
        Scenario(
            "both pressed",
            *both_pressed(),
            duration="6s",
            description="the two buttons pressed together, in either order and in the same instant; "
            "OFF released while ON is held",
        ),
    ],
    checks=[
        always(implies(all_of(ZAP, off(VYP)), "LED")).named("the ON button alone switches the LED on within 1 scan"),
        always(implies(VYP, off("LED"))).named("the OFF button switches the LED off, also when both are pressed"),
        holds("LED").until(becomes(VYP)).named("releasing the ON button leaves the LED on"),
        holds(off("LED")).until(becomes(all_of(ZAP, off(VYP)))).named("releasing the OFF button leaves the LED off"),
        program_uses_no("SET").named("no SET instruction"),
        program_uses_no("RESET").named("no RESET instruction"),
    ],
    requirements={
        "the ON button alone switches the LED on within 1 scan": (
            "pressing TLACIDLO_ZAP switches the LED on, in the scan that sees it"
        ),
        "the OFF button switches the LED off, also when both are pressed": (
            "When both buttons are pressed, the output is off"
        ),
        "releasing the ON button leaves the LED on": "releasing it does not affect the LED (it stays lit)",
        "releasing the OFF button leaves the LED off": (
            "Pressing TLACIDLO_VYP switches the LED off; releasing it does not affect the LED"
        ),
        "no SET instruction": "Implement the program without SET and RESET",
        "no RESET instruction": "Implement the program without SET and RESET",
    },
    solutions=[
        solution(NUMBER, "reference", explanation="(ZAP OR LED) AND NOT VYP: self-holding, stop-dominant"),
        solution(
            NUMBER,
            "wrong-start-dominant",
            "wrong",
            "the OFF contact sits in the self-holding branch only: with both buttons pressed the LED is on",
            fails=("the OFF button switches the LED off, also when both are pressed",),
        ),
        solution(
            NUMBER,
            "wrong-set-reset",
            "wrong",
            "right behaviour, but built from the forbidden SET and RESET",
            fails=("no SET instruction", "no RESET instruction"),
        ),
    ],
    notes=(
        "'Unchanged when neither button is pressed' is checked as two statements: once on, the LED stays on until "
        "a scan sees the OFF button; once off, it stays off until a scan sees the ON button without the OFF one."
    ),
)
