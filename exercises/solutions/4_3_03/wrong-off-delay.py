"""A typical slip (not from the textbook): an off-delay timer in place of the self-holding contact.

LED := TOF(IN := TLACIDLO, PT := 5 s).Q lights the LED with the press and keeps it lit after the
release, which looks like a latch in a short test; but 5 s after the release the LED goes out,
while the task wants it lit for good ("there is no switch-off condition").
"""

T_OFF = IEC_TIMER()


def OB1(t):
    t.LED = t.T_OFF.TOF(IN=t.TLACIDLO, PT="5s")
