"""Buggy: ALARM set from the timer's Q as a coil-like assignment, ALARM := Q OR (ALARM AND ACK): the
acknowledgement logic inverted, so ACK holds the alarm and releasing it clears it."""

WATCHDOG = IEC_TIMER()


def start_belt(t):
    if t.S1:
        t.D1 = True


def watchdog(t):
    t.ALARM = t.WATCHDOG.TON(IN=t.D1 and not t.S2, PT="10s") or (t.ALARM and t.ACK)


def stop_belt(t):
    if t.S2 or t.WATCHDOG.Q or t.ALARM:
        t.D1 = False


OB1 = [start_belt, watchdog, stop_belt]
