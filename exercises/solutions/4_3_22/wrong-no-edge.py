"""A typical slip (not from the textbook): a plain NO contact instead of the edge.

The ADD runs in every OB30 call that finds TL pressed, so a press held over several calls is
counted several times.
"""


def count_presses(t):
    if t.TL:
        t.D.CISLO = t.D.CISLO + 1  # ADD


OB30 = CyclicInterrupt(count_presses, period="1s")
