"""A typical slip (not from the textbook): SET and RESET, the instructions the task forbids.

The RESET rung comes last, so it wins when both buttons are pressed and the behaviour is right;
the exercise is about building the same memory from contacts and a coil.
"""


def switch_on(t):
    if t.TLACIDLO_ZAP:
        t.LED = True  # S LED


def switch_off(t):
    if t.TLACIDLO_VYP:
        t.LED = False  # R LED


OB1 = [switch_on, switch_off]
