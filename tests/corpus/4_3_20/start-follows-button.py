"""Buggy: START assigned in an if/else from TL (a coil written out): it drops with the release."""


def copy_start(t):
    t.LED = t.START


def set_start(t):
    if t.TL:
        t.START = True
    else:
        t.START = False


OB30 = CyclicInterrupt([copy_start, set_start], period="1s")
