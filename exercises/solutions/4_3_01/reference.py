"""4.3.1, solution 1: a NO contact drives the coil (LED := TLACIDLO)."""


def OB1(t):
    t.LED = t.TLACIDLO
