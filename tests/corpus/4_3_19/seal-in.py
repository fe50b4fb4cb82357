"""Correct: the LED held by its own contact (LED := LED OR TL) instead of S LED, in OB30 (1 s)."""


def latch(t):
    t.LED = t.LED or t.TL


OB30 = CyclicInterrupt([latch], period="1s")
