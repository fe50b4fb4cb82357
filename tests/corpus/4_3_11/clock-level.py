"""Buggy: Clock_1Hz copied without an edge: TRUE for 0.5 s at a time, not one scan."""


def OB1(t):
    t.Takt1s = t.Clock_1Hz
