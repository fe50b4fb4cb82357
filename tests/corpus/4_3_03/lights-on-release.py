"""Buggy: the edge detector on the wrong edge (F_TRIG): the LED lights when the button is released."""

RELEASE = F_TRIG()


def OB1(t):
    t.LED = t.RELEASE.F_TRIG(CLK=t.TLACIDLO) or t.LED
