"""A typical slip (not from the textbook): 4.3.1's program reused for the NC button.

LED := TLACIDLO. With the NC wiring the input is TRUE while the button is *not* pressed, so the LED
is lit at rest and goes out exactly while the button is pressed: the inverse of the task.
"""


def OB1(t):
    t.LED = t.TLACIDLO
