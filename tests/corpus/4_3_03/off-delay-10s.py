"""Buggy: an off-delay timer of 10 s passes for a latch in a short test, but the LED goes out 10 s after
the release."""

HOLD = IEC_TIMER()


def OB1(t):
    t.LED = t.HOLD.TOF(IN=t.TLACIDLO, PT="10s")
