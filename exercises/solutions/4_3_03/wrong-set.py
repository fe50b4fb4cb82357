"""A typical slip (not from the textbook): the latch built with SET.

``IF TLACIDLO THEN S LED`` behaves exactly as the task asks, but the task forbids the SET
instruction: the exercise is about the self-holding contact.
"""


def OB1(t):
    if t.TLACIDLO:
        t.LED = True  # S LED
