"""Buggy: the N contact (falling edge) taken for the P contact: the count comes at the release."""


def count_presses(t):
    if N(t.TL, "SB1"):
        t.D.CISLO = t.D.CISLO + 1


OB30 = CyclicInterrupt(count_presses, period="1s")
