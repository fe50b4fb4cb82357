"""A typical slip (not from the textbook): the OFF contact inside the self-holding branch.

LED := TLACIDLO_ZAP OR (LED AND NOT TLACIDLO_VYP) switches on and off, but when both buttons are
pressed the ON button wins (start-dominant); the task wants the output off.
"""


def OB1(t):
    t.LED = t.TLACIDLO_ZAP or (t.LED and not t.TLACIDLO_VYP)
