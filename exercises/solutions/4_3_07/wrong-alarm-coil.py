"""Wrong (the textbook's remark on version 1): ALARM as a plain assignment coil of the timer's Q.

TON_A.Q is TRUE for one scan only (in the next scan D1 is FALSE and the timer resets), so a coil
ALARM := TON_A.Q is TRUE for that one scan, 1 ms: the alarm is not latched and no operator would ever
see it. It must be a SET coil, reset by ACK.
"""

TON_A = IEC_TIMER()


def start_belt(t):
    """Rung 1: an object at S1 sets D1."""
    if t.S1:
        t.D1 = True  # S D1


def watchdog(t):
    """Rung 2: TON_A(IN := D1 AND NOT S2, PT := 10 s); ALARM := Q."""
    t.ALARM = t.TON_A.TON(IN=t.D1 and not t.S2, PT="10s")


def stop_belt(t):
    """Rung 3: S2 OR TON_A.Q resets D1."""
    if t.S2 or t.TON_A.Q:
        t.D1 = False  # R D1


def acknowledge(t):
    """Rung 4: ACK resets ALARM."""
    if t.ACK:
        t.ALARM = False  # R ALARM


OB1 = [start_belt, watchdog, stop_belt, acknowledge]
