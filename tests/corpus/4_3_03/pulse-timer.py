"""Buggy: a pulse timer (TP, 5 s) read as "keep the LED lit": it goes out 5 s after the press."""

PULSE = IEC_TIMER()


def OB1(t):
    t.LED = t.PULSE.TP(IN=t.TLACIDLO, PT="5s")
