"""Correct: the belt as one if/elif chain, S2 (stop) tested first, so the RESET wins."""


def OB1(t):
    if t.S2:
        t.D1 = False
    elif t.S1:
        t.D1 = True
