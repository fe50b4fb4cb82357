"""Buggy: the program put in OB1: the LED lights one scan after the press, not at the next call."""


def copy_start(t):
    t.LED = t.START


def set_start(t):
    if t.TL:
        t.START = True


OB1 = [copy_start, set_start]
