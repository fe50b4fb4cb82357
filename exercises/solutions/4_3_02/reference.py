"""4.3.2, solution 1: an NC contact drives the coil (LED := NOT TLACIDLO).

The button is wired NC, so the input is FALSE while it is pressed; the negated contact turns that
back into "pressed".
"""


def OB1(t):
    t.LED = not t.TLACIDLO
