"""Buggy: the NO contact read as NC (LED := NOT TLACIDLO): the LED is lit while the button is up."""


def OB1(t):
    t.LED = not t.TLACIDLO
