"""Correct (version 3 as criterion 4 words it): the belt starts on the rising edge of S1 (R_TRIG), so
after ACK it waits for a new S1 edge; the alarm blocks it; ACK clears the alarm."""

WATCHDOG = IEC_TIMER()
LOADED = R_TRIG()


def start_belt(t):
    if t.LOADED.R_TRIG(CLK=t.S1) and not t.ALARM:
        t.D1 = True


def watchdog(t):
    if t.WATCHDOG.TON(IN=t.D1 and not t.S2, PT="10s"):
        t.ALARM = True


def stop_belt(t):
    if t.S2 or t.ALARM:
        t.D1 = False


def acknowledge(t):
    if t.ACK:
        t.ALARM = False


OB1 = [start_belt, watchdog, stop_belt, acknowledge]
