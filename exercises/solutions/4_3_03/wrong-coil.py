"""A typical slip (not from the textbook): a plain coil without the self-holding branch.

LED := TLACIDLO is 4.3.1 again: the LED goes out as soon as the button is released.
"""


def OB1(t):
    t.LED = t.TLACIDLO
