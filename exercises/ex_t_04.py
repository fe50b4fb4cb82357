"""T-04 The 3-to-8 decoder by a table (the manual's EX-24, LTB). Plant: PANEL.

The manual (§7.7): "convert the binary code on C, B, A (A the least significant bit) to the 1-of-8 code on
Y0", by packing the three inputs into a number with STK, masking it with ``and %111`` and reading the byte
table ``dekodér`` with LTB; the test vector it implies: X0 = 05H gives Y0 = 20H.
"""

from exercises._tecomat import il_solution
from plants import Panel
from plcsim.check import all_of, always, implies, off
from plcsim.exercise import IO, Exercise
from plcsim.scenario import Scenario, switch

NUMBER = "T-04"
ONE_OF_EIGHT = "code n lights the lamp vystupn (Y0.n) and no other"
"""What every check grades, in the task's words."""
INPUTS = ("a", "b", "c")
LAMPS = tuple(f"vystup{n}" for n in range(8))
GRAY = (0, 1, 3, 2, 6, 7, 5, 4)
JUMPS = (0, 5, 2, 7, 0, 6, 1, 4, 3, 0)


def lights(n: int) -> str:
    return f"c b a = {n:03b} lights vystup{n} alone (Y0 = {1 << n:02X}H)"


def codes(sequence: tuple[int, ...], start_ms: int, step_ms: int = 400) -> list:
    """Set the switches to each code of ``sequence`` in turn, ``step_ms`` apart; each switch that changes does
    so at its own seeded instant in the first 50 ms of the step (the code passes through the codes between)."""
    actions: list = []
    previous = 0
    for k, code in enumerate(sequence):
        t = start_ms + k * step_ms
        for bit, name in enumerate(INPUTS):
            if (code ^ previous) >> bit & 1:
                actions.append(switch(name, bool(code >> bit & 1), t=f"{t}ms..{t + 50}ms"))
        previous = code
    return actions


def code_is(n: int):
    return all_of(*(name if n >> bit & 1 else off(name) for bit, name in enumerate(INPUTS)))


EXERCISE = Exercise(
    number=NUMBER,
    slug="tecomat-decoder",
    title="3-to-8 decoder by a table (Tecomat EX-24)",
    title_sk="Tecomat, příklad EX-24 – dekodér 1 z 8",
    task=(
        "Three switches give a binary code: c (X0.2) the most significant bit, b (X0.1), a (X0.0) the least "
        "significant one. Convert it to the 1-of-8 code on the output byte Y0: code n lights the lamp vystupn "
        "(Y0.n) and no other (c b a = 101, X0 = 05H, gives Y0 = 20H). Write it in the Tecomat's instruction list "
        "with a byte table (#table byte) read by LTB."
    ),
    io=[
        *(
            IO(name, f"code bit {name.upper()} (weight {1 << bit})", "Bool", f"%I0.{bit}", "NO", comment=f"X0.{bit}")
            for bit, name in enumerate(INPUTS)
        ),
        *(
            IO(lamp, f"output {n} of the 1-of-8 code", "Bool", f"%Q0.{n}", comment=f"Y0.{n}")
            for n, lamp in enumerate(LAMPS)
        ),
    ],
    rig=lambda: Panel(buttons=(), switches=INPUTS, lamps=LAMPS),
    scenarios=[
        Scenario(
            "every code",
            *codes(GRAY, 200),
            duration="3.5s",
            description="the eight codes in Gray order (one switch changes at a time)",
        ),
        Scenario(
            "jumps",
            *codes(JUMPS, 200),
            duration="4.5s",
            description="codes far apart, several switches changing at seeded instants within 50 ms",
        ),
    ],
    checks=[
        always(implies(code_is(n), all_of(LAMPS[n], *(off(lamp) for lamp in LAMPS if lamp != LAMPS[n])))).named(
            lights(n)
        )
        for n in range(8)
    ],
    requirements={
        "c b a = 000 lights vystup0 alone (Y0 = 01H)": ONE_OF_EIGHT,
        "c b a = 001 lights vystup1 alone (Y0 = 02H)": ONE_OF_EIGHT,
        "c b a = 010 lights vystup2 alone (Y0 = 04H)": ONE_OF_EIGHT,
        "c b a = 011 lights vystup3 alone (Y0 = 08H)": ONE_OF_EIGHT,
        "c b a = 100 lights vystup4 alone (Y0 = 10H)": ONE_OF_EIGHT,
        "c b a = 101 lights vystup5 alone (Y0 = 20H)": ONE_OF_EIGHT,
        "c b a = 110 lights vystup6 alone (Y0 = 40H)": ONE_OF_EIGHT,
        "c b a = 111 lights vystup7 alone (Y0 = 80H)": ONE_OF_EIGHT,
    },
    solutions=[
        il_solution(NUMBER, "reference", explanation="EX-24 as printed: LD c, LD b, LD a, STK, AND %111, LTB, WR Y0"),
        il_solution(
            NUMBER,
            "wrong-bit-order",
            "wrong",
            "the inputs pushed a, b, c: STK puts the last one pushed (A0) lowest, so a becomes the MSB",
            fails=tuple(lights(n) for n in (1, 3, 4, 6)),
        ),
        il_solution(
            NUMBER,
            "wrong-no-stk",
            "wrong",
            "without STK the mask takes a's level alone (0000H or FFFFH), so only vystup0 or vystup7 lights",
            fails=tuple(lights(n) for n in range(1, 7)),
        ),
    ],
)
