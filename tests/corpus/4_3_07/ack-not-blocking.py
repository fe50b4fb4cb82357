"""Buggy: version 3 meant, version 2 written: the alarm does not block the belt, so an object loaded
during the alarm starts it before ACK."""

WATCHDOG = IEC_TIMER()


def start_belt(t):
    if t.S1:
        t.D1 = True


def watchdog(t):
    if t.WATCHDOG.TON(IN=t.D1 and not t.S2, PT="10s"):
        t.ALARM = True


def stop_belt(t):
    if t.S2 or t.WATCHDOG.Q:
        t.D1 = False


def acknowledge(t):
    if t.ACK:
        t.ALARM = False


OB1 = [start_belt, watchdog, stop_belt, acknowledge]
