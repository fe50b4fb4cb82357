"""Correct: START held by its own contact (START := START OR TL) instead of S START; same behaviour."""


def copy_start(t):
    t.LED = t.START


def hold_start(t):
    t.START = t.START or t.TL


OB30 = CyclicInterrupt([copy_start, hold_start], period="1s")
