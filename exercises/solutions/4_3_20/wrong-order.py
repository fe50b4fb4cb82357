"""A typical slip (not from the textbook): the two networks in the opposite order.

With TL -> S START first, the LED := START network sees the new START in the same call, so the LED
comes at the call that sees the button, one period earlier than in the textbook's program: the
order of the networks is the point of the exercise.
"""


def set_start(t):
    if t.TL:
        t.START = True  # S START


def copy_start(t):
    t.LED = t.START


OB30 = CyclicInterrupt([set_start, copy_start], period="1s")
