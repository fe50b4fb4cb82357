"""Buggy: the self-holding contact in series instead of in parallel: the LED never lights."""


def OB1(t):
    t.LED = t.TLACIDLO and t.LED
