"""4.3.4, the textbook's solution: 4.3.3's self-holding contact plus an NC contact of the OFF button
in series, LED := (TLACIDLO_ZAP OR LED) AND NOT TLACIDLO_VYP.

The OFF button's contact is outside the OR, so it wins when both buttons are pressed (stop-dominant).
"""


def OB1(t):
    t.LED = (t.TLACIDLO_ZAP or t.LED) and not t.TLACIDLO_VYP
