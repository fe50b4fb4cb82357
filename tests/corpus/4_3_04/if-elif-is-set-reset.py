"""Buggy: stop-dominant as an if/elif chain, thought to avoid SET and RESET; but a coil written only
under a condition keeps its value otherwise, which is what the S and R coils are: the static checks
read the two branches as RESET LED and SET LED."""


def OB1(t):
    if t.TLACIDLO_VYP:
        t.LED = False
    elif t.TLACIDLO_ZAP:
        t.LED = True
