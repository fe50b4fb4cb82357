"""Buggy: the button in series with the copy, LED := START AND TL: the LED goes out with the release."""


def copy_start(t):
    t.LED = t.START and t.TL


def set_start(t):
    if t.TL:
        t.START = True


OB30 = CyclicInterrupt([copy_start, set_start], period="1s")
