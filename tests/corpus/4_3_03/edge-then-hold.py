"""Correct: the press taken through an R_TRIG, then held by the LED's own contact.

The R_TRIG's Q is TRUE in the first scan that sees the button, so the LED lights in that scan; the
self-holding branch keeps it lit. No SET instruction.
"""

PRESS = R_TRIG()


def OB1(t):
    t.LED = t.PRESS.R_TRIG(CLK=t.TLACIDLO) or t.LED
