"""Buggy: LED := TL as a plain coil in OB30: the LED follows the button at each call and goes out."""


def copy(t):
    t.LED = t.TL


OB30 = CyclicInterrupt([copy], period="1s")
