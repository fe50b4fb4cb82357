"""T-03 Counting products on a belt with CTU (the manual's EX-15). Plant: CONV1.

The manual (§7.5.1): "count the products on a belt; the sensor on X0.0, the reset button on X0.1", with
``ld snimac / ld nuluj / ctu citac``. The counter counts a rising edge of its count input (relative to its
previous activation) and holds 0 while its reset input is on. Here the products ride CONV1 past its first
light barrier S1, and the belt is the program's to keep running.
"""

from exercises._tecomat import CountedSinceReset, il_solution
from plants import Conv1
from plcsim.check import always, final, implies, value
from plcsim.exercise import IO, Exercise, only
from plcsim.scenario import Scenario, place, press

NUMBER = "T-03"
COUNTS = "citac is the number of products that reached S1 since the last reset, in every cycle"
TOTAL = "after eight products citac is 8"
RESET = "nuluj clears citac and holds it at 0 while pressed"


def products(first: int, n: int, name: str = "p") -> list:
    """``n`` products put on the belt's start, the first at ``first`` ms, then one every 1.5..2.5 s (seeded), so
    that each passes S1 as a pulse of its own (a product covers S1 for about 0.6 s)."""
    return [
        place(
            f"{name}{k + 1}", at="belt", t=f"{first + 2000 * k}ms..{first + 2000 * k + 500}ms", offset_mm=(16.0, 20.0)
        )
        for k in range(n)
    ]


EXERCISE = Exercise(
    number=NUMBER,
    slug="tecomat-product-counter",
    title="Product counter with CTU (Tecomat EX-15)",
    title_sk="Tecomat, příklad EX-15 – čítání výrobků",
    task=(
        "Products ride the conveyor past the light barrier S1 (input snimac, X0.0, NO: TRUE while a product "
        "interrupts it). Count them in the counter word citac (RW10) with CTU: each product that reaches the "
        "sensor adds 1. The push-button nuluj (X0.1, NO) clears the count; while it is held the count stays 0. "
        "Keep the belt running (output dopravnik, Y0.2, TRUE in every cycle). Write it in the Tecomat's "
        "instruction list."
    ),
    io=[
        IO("snimac", "product sensor", "Bool", "%I0.0", "NO", signal="S1", comment="X0.0 as in EX-15; CONV1's S1"),
        IO("nuluj", "reset push-button", "Bool", "%I0.1", "NO", comment="X0.1 as in EX-15"),
        IO("dopravnik", "conveyor forward", "Bool", "%Q0.2", signal="D1", comment="Y0.2, CONV1's D1; not in EX-15"),
        IO("citac", "product counter", "Word", "%MW10", comment="RW10; EX-15 declares it with #reg word citac"),
    ],
    rig=lambda: Conv1(buttons=("nuluj",)),
    scenarios=[
        Scenario(
            "eight products",
            *products(300, 8),
            duration="19s",
            description="eight products put on the running belt 1.5..2.5 s apart: the count reaches 8",
        ),
        Scenario(
            "reset",
            *products(300, 3),
            *press("nuluj", t="6.3s..6.5s", hold="1.2s..1.5s"),
            place("q1", at="belt", t="6.6s", offset_mm=(16.0, 20.0)),
            *products(9000, 3, "r"),
            *press("nuluj", t="15.5s..16s", hold="100ms..300ms"),
            duration="17s",
            description="three products, a reset, a product passing S1 while nuluj is held (not counted), "
            "three more products, a last reset",
        ),
    ],
    checks=[
        always(CountedSinceReset("citac", "snimac", "nuluj")).named(COUNTS),
        only(final("citac").equals(8).named(TOTAL), "eight products"),
        only(always(implies("nuluj", value("citac") == 0)).named(RESET), "reset"),
    ],
    requirements={
        "citac is the number of products that reached S1 since the last reset, in every cycle": (
            "each product that reaches the sensor adds 1"
        ),
        "after eight products citac is 8": "each product that reaches the sensor adds 1",
        "nuluj clears citac and holds it at 0 while pressed": "clears the count; while it is held the count stays 0",
    },
    solutions=[
        il_solution(NUMBER, "reference", explanation="EX-15 as printed (LD snimac, LD nuluj, CTU citac), D1 on"),
        il_solution(
            NUMBER,
            "wrong-level-count",
            "wrong",
            "the count fed a level instead of an edge: ADD 1 in every cycle the sensor is covered counts each "
            "product some 600 times",
            fails=(COUNTS, TOTAL),
        ),
        il_solution(
            NUMBER,
            "wrong-swapped-inputs",
            "wrong",
            "the inputs in the wrong stack levels: CTU counts A1 and resets on A0, so it counts the button "
            "and a product resets it",
            fails=(COUNTS, TOTAL, RESET),
        ),
    ],
)
