"""Buggy: the alarm is raised but nothing stops the belt except S2: a jammed belt runs on."""

WATCHDOG = IEC_TIMER()


def start_belt(t):
    if t.S1:
        t.D1 = True


def watchdog(t):
    if t.WATCHDOG.TON(IN=t.D1 and not t.S2, PT="10s"):
        t.ALARM = True


def stop_belt(t):
    if t.S2:
        t.D1 = False


def acknowledge(t):
    if t.ACK:
        t.ALARM = False


OB1 = [start_belt, watchdog, stop_belt, acknowledge]
