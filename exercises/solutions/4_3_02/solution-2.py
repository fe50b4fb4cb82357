"""4.3.2, solution 2: SET on the NC contact (pressed), RESET on the NO contact (released).

Both rungs run in every scan: while the button is pressed the first one sets the LED, while it is
released the second one resets it.
"""


def pressed(t):
    if not t.TLACIDLO:
        t.LED = True  # S LED


def released(t):
    if t.TLACIDLO:
        t.LED = False  # R LED


OB1 = [pressed, released]
