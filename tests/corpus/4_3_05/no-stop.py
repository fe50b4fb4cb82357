"""Buggy: nothing resets D1: the object is carried past S2 and off the end of the belt."""


def OB1(t):
    if t.S1:
        t.D1 = True
