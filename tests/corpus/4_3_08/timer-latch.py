"""Buggy: a timer blinker whose lamp is set and reset inside IF ALARM: after ACK the lamp keeps the
phase it had, lit if the operator acknowledged during a flash."""

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
    if t.BLINK.TON(IN=t.ALARM, PT="1s"):
        RT(t.BLINK)
    if t.ALARM:
        if t.BLINK.ET > TIME("500ms"):
            t.LED = True
        else:
            t.LED = False


OB1 = [alarm, lamp]
