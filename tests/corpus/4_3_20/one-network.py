"""Correct: both rungs in one OB30 network, in the textbook's order (copy first, then set)."""


def program(t):
    t.LED = t.START
    if t.TL:
        t.START = True


OB30 = CyclicInterrupt([program], period="1s")
