"""4.3.3 Latching the LED without SET. Plant: PANEL."""

from exercises._common import solution
from plants import Panel
from plcsim.check import action, always, holds, implies, off, program_uses_no
from plcsim.exercise import IO, Exercise
from plcsim.scenario import Scenario, press, start_cpu, stop_cpu

NUMBER = "4.3.3"


def presses(first: str, n: int, gap_ms: int = 400) -> list:
    """A first press at a seeded time ``first`` (2..150 ms long) and ``n - 1`` more in later windows."""
    actions = list(press("TLACIDLO", t=first, hold="2ms..150ms"))
    start = 1000
    for _ in range(n - 1):
        actions += press("TLACIDLO", t=f"{start}ms..{start + 100}ms", hold="2ms..200ms")
        start += gap_ms
    return actions


EXERCISE = Exercise(
    number=NUMBER,
    slug="led-latch",
    title="Latching the LED without SET",
    title_sk="Príklad 3 – Zapnutie LED bez SET",
    task=(
        "The push-button TLACIDLO (push-button) is wired as a normally open (NO) contact; the output LED (lamp) "
        "lights a lamp.\n"
        "Task: pressing the button switches the LED on, in the first scan that sees the button; after the button is "
        "released the LED stays lit. Until the button is first pressed the LED is off. "
        "Implement the program without the SET instruction. (The task has no switch-off condition.)"
    ),
    io=[
        IO("TLACIDLO", "push-button", "Bool", "%I0.0", "NO", comment="address proposed; the textbook gives none"),
        IO("LED", "lamp", "Bool", "%Q0.0", comment="address proposed"),
    ],
    rig=lambda: Panel(buttons=("TLACIDLO",), switches=(), lamps=("LED",)),
    scenarios=[
        Scenario(
            "presses",
            *presses("300ms..800ms", 5),
            duration="3s",
            description="a first press at a seeded time, then four more; presses of 2..200 ms",
        ),
        Scenario(
            "stop and restart",
            *press("TLACIDLO", t="200ms..600ms", hold="2ms..150ms"),
            stop_cpu(t="1s..1.4s"),
            start_cpu(t="1.6s..2s"),
            *press("TLACIDLO", t="2.5s..3s", hold="2ms..150ms"),
            duration="4s",
            description="latch, CPU to STOP and back to RUN (the LED is off again), press again",
        ),
        Scenario(
            "long wait",
            *press("TLACIDLO", t="200ms..2s", hold="2ms..1.5s"),
            *press("TLACIDLO", t="3s..6s", hold="2ms..1.5s"),
            duration="40s",
            description="two presses at seeded times, then more than 30 s without one: a latch that is only an "
            "off-delay goes out",
        ),
    ],
    checks=[
        holds(off("LED")).until(action("press", "TLACIDLO")).named("the LED stays off until the button is pressed"),
        always(implies("TLACIDLO", "LED")).named("the LED lights in the first scan that sees the button"),
        holds("LED").until(action("stop_cpu")).named("once lit, the LED stays lit (until the CPU is stopped)"),
        program_uses_no("SET").named("no SET instruction"),
    ],
    requirements={
        "the LED stays off until the button is pressed": "Until the button is first pressed the LED is off",
        "the LED lights in the first scan that sees the button": (
            "pressing the button switches the LED on, in the first scan that sees the button"
        ),
        "once lit, the LED stays lit (until the CPU is stopped)": "after the button is released the LED stays lit",
        "no SET instruction": "Implement the program without the SET instruction",
    },
    solutions=[
        solution(NUMBER, "reference", explanation="self-holding contact: LED := TLACIDLO OR LED"),
        solution(
            NUMBER,
            "wrong-set",
            "wrong",
            "the latch works, but with the forbidden SET instruction",
            fails=("no SET instruction",),
        ),
        solution(
            NUMBER,
            "wrong-coil",
            "wrong",
            "a plain coil: the LED goes out when the button is released",
            fails=("once lit, the LED stays lit (until the CPU is stopped)",),
        ),
        solution(
            NUMBER,
            "wrong-off-delay",
            "wrong",
            "an off-delay timer (TOF, 5 s) in place of the seal-in: the LED goes out 5 s after the release",
            fails=("once lit, the LED stays lit (until the CPU is stopped)",),
        ),
    ],
    notes=(
        "Acceptance criterion 3 (after STOP->RUN the LED is off until the next press) is the 'stop and restart' "
        "scenario: outputs and the non-retentive output image are cleared at STOP->RUN, so the seal-in branch "
        "starts FALSE. The trace keeps the output image during STOP (the physical outputs are off), so 'once lit' "
        "is checked until the stop action rather than until the first STOP row. Criterion 1's 'for the rest of the "
        "run' is what the 'long wait' scenario watches: the last release comes by 7.5 s and the run lasts 40 s, so "
        "an off-delay in place of the seal-in is caught on every seed unless its preset exceeds 32.5 s."
    ),
)
