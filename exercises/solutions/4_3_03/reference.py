"""4.3.3, the textbook's solution: a self-holding (seal-in) contact, LED := TLACIDLO OR LED.

In the first scan with the button pressed only the upper branch (TLACIDLO) is TRUE; from the next
scan on both are; after the release the lower branch (the LED's own contact) keeps the coil TRUE.
The task has no switch-off condition.
"""


def OB1(t):
    t.LED = t.TLACIDLO or t.LED
