"""Buggy: the button through an R_TRIG: the LED lights for one scan per press instead of while held."""

PRESS = R_TRIG()


def OB1(t):
    t.LED = t.PRESS.R_TRIG(CLK=t.TLACIDLO)
