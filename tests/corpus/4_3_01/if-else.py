"""Correct: the coil written out as if/else on the button."""


def OB1(t):
    if t.TLACIDLO:
        t.LED = True
    else:
        t.LED = False
