"""Buggy: the protection time typed as 4 s: every normal transport (4.8 s) raises a false alarm."""

WATCHDOG = IEC_TIMER()


def start_belt(t):
    if t.S1:
        t.D1 = True


def watchdog(t):
    if t.WATCHDOG.TON(IN=t.D1 and not t.S2, PT="4s"):
        t.ALARM = True


def stop_belt(t):
    if t.S2 or t.WATCHDOG.Q or t.ALARM:
        t.D1 = False


def acknowledge(t):
    if t.ACK:
        t.ALARM = False


OB1 = [start_belt, watchdog, stop_belt, acknowledge]
