"""Buggy: the edge of Clock_2Hz: one scan every 0.5 s, twice as many pulses."""

EDGE = R_TRIG()


def OB1(t):
    t.Takt1s = t.EDGE.R_TRIG(CLK=t.Clock_2Hz)
