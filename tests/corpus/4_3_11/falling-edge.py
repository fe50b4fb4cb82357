"""Correct: the falling edge of Clock_1Hz (F_TRIG) is also one scan every 1 s."""

EDGE = F_TRIG()


def OB1(t):
    t.Takt1s = t.EDGE.F_TRIG(CLK=t.Clock_1Hz)
