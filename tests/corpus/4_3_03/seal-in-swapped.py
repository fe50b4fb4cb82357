"""Correct: the self-holding branch written first, LED := LED OR TLACIDLO."""


def OB1(t):
    t.LED = t.LED or t.TLACIDLO
