"""Correct: the classic two-timer blinker: ON_T times the lit phase, OFF_T the dark one; each restarts
the other. Each phase lasts 0.5 s plus a scan."""

ON_T = IEC_TIMER()
OFF_T = IEC_TIMER()

WATCHDOG = IEC_TIMER()


def alarm(t):
    if t.S1:
        t.D1 = True
    if t.WATCHDOG.TON(IN=t.D1 and not t.S2, PT="10s"):
        t.ALARM = True
    if t.S2 or t.WATCHDOG.Q or t.ALARM:
        t.D1 = False
    if t.ACK:
        t.ALARM = False


def blinker(t):
    t.ON_T.TON(IN=t.ALARM and not t.OFF_T.Q, PT="500ms")
    t.OFF_T.TON(IN=t.ON_T.Q, PT="500ms")
    t.LED = t.ALARM and not t.ON_T.Q


OB1 = [alarm, blinker]
