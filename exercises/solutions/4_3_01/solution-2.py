"""4.3.1, solution 2: an NC contact and a negated coil, LED := NOT(NOT TLACIDLO).

The textbook shows it only to show the possibility: it is more complicated and less readable.
"""


def OB1(t):
    t.LED = not (not t.TLACIDLO)
