"""Buggy: the blink timer never restarted (no RT): after 0.5 s the LED stays lit."""

BLINK = IEC_TIMER()

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
    t.BLINK.TON(IN=t.ALARM, PT="1s")
    t.LED = t.BLINK.ET > TIME("500ms")


OB1 = [alarm, lamp]
