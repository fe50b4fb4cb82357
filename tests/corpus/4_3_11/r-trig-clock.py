"""Correct: the rising edge of Clock_1Hz found by an R_TRIG instance instead of the P contact."""

EDGE = R_TRIG()


def OB1(t):
    t.Takt1s = t.EDGE.R_TRIG(CLK=t.Clock_1Hz)
