"""Correct: the belt started on the rising edge of S1 (R_TRIG) and stopped at S2."""

LOADED = R_TRIG()


def start_belt(t):
    if t.LOADED.R_TRIG(CLK=t.S1):
        t.D1 = True


def stop_belt(t):
    if t.S2:
        t.D1 = False


OB1 = [start_belt, stop_belt]
