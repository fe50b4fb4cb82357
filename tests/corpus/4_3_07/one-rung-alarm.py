"""Correct: the SET of ALARM in the same rung as the RESET of D1 (the spec's "keeps the SET in the same
rung as the RESET"), the belt control as one if/elif chain, reset-dominant."""

WATCHDOG = IEC_TIMER()


def belt(t):
    if t.S2 or t.ALARM:
        t.D1 = False
    elif t.S1:
        t.D1 = True


def watchdog(t):
    if t.WATCHDOG.TON(IN=t.D1 and not t.S2, PT="10s"):
        t.ALARM = True
        t.D1 = False


def acknowledge(t):
    if t.ACK:
        t.ALARM = False


OB1 = [belt, watchdog, acknowledge]
