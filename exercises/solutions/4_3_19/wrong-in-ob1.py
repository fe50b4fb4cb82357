"""A typical slip (not from the textbook): the network put in OB1 instead of OB30.

In the program cycle the button is read every millisecond, so the LED comes within a scan of the
press and even a short press between two OB30 calls lights it: the behaviour the exercise contrasts
with the periodic task.
"""


def set_led(t):
    if t.TL:
        t.LED = True  # S LED


OB1 = [set_led]
