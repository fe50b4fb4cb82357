"""Buggy: the LED wired to the clock bit alone: it blinks with no alarm at all."""

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
    t.LED = t.Clock_1Hz


OB1 = [alarm, lamp]
