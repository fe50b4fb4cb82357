"""Correct: the seal-in split over two networks, the second one a plain copy of the first's result."""


def hold(t):
    t.LED = t.TLACIDLO or t.LED


def keep(t):
    t.LED = t.LED and True


OB1 = [hold, keep]
