"""4.3.20, the textbook's program (Fig. 4.180) in OB30, networks in this order (the textbook: "the
program runs top to bottom"): LED := START, then TL -> S START.

The call that sees TL sets START; only the next call (1 s later) copies START to the LED, so the LED
comes 1 s to 2 s after the press.
"""


def copy_start(t):
    """Network 1: LED := START."""
    t.LED = t.START


def set_start(t):
    """Network 2: TL -> S START."""
    if t.TL:
        t.START = True  # S START


OB30 = CyclicInterrupt([copy_start, set_start], period="1s")
