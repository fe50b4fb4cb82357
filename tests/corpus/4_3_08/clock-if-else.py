"""Correct: solution 1 written as if/else on ALARM AND Clock_1Hz; the alarm of 4.3.7 in one network."""

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


def lamp(t):
    if t.ALARM and t.Clock_1Hz:
        t.LED = True
    else:
        t.LED = False


OB1 = [alarm, lamp]
