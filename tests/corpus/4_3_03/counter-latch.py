"""Buggy: the presses counted (CTU) and the LED lit while the count is above zero. The counter's
instance is retentive, so after STOP->RUN the LED is lit again before any press."""

PRESSES = IEC_COUNTER()


def OB1(t):
    t.PRESSES.CTU(CU=t.TLACIDLO, R=False, PV=1)
    t.LED = t.PRESSES.CV > 0
