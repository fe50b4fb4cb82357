"""A typical slip (not from the textbook): SET without the matching RESET.

The LED comes on with the first press and never goes out, so it does not follow the button.
"""


def OB1(t):
    if t.TLACIDLO:
        t.LED = True
