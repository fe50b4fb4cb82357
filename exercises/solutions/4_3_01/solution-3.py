"""4.3.1, solution 3: SET while pressed, RESET while released (both run every scan)."""


def pressed(t):
    if t.TLACIDLO:
        t.LED = True  # S LED


def released(t):
    if not t.TLACIDLO:
        t.LED = False  # R LED


OB1 = [pressed, released]
