"""A typical slip (not from the textbook): the edge network in OB1 instead of OB30.

In the program cycle the button is read every millisecond, so the short press between two OB30
calls (case a, 0.1 s ... 0.6 s) is counted too: the behaviour the exercise contrasts with the
periodic task.
"""


def count_presses(t):
    if P(t.TL, "SB1"):
        t.D.CISLO = t.D.CISLO + 1  # ADD


OB1 = [count_presses]
