"""Wrong: version 2 with the reset rung before the TON box (the scan-order trap, catalogue analysis).

Rung 2 reads TON_A.Q before rung 3 runs the timer. On an S7-1200 a read of Q (or ET) refreshes the
instance (textbook 3.6.1, 4.3.11 solution 4): in the scan in which 10 s have elapsed, rung 2 already
sees Q = TRUE and resets D1; then the TON box gets IN = D1 AND NOT S2 = FALSE and resets, so its Q
output is FALSE and the SET of ALARM hung on it never executes. The belt stops, but no alarm is ever
raised. (A simulator that updated the timer only at the box would hide the mistake.)
"""

TON_A = IEC_TIMER()


def start_belt(t):
    """Rung 1: an object at S1 sets D1."""
    if t.S1:
        t.D1 = True  # S D1


def stop_belt(t):
    """Rung 2: S2 OR TON_A.Q resets D1 (reads Q before the box of rung 3 has run)."""
    if t.S2 or t.TON_A.Q:
        t.D1 = False  # R D1


def watchdog(t):
    """Rung 3: TON_A(IN := D1 AND NOT S2, PT := 10 s); Q -> S ALARM."""
    if t.TON_A.TON(IN=t.D1 and not t.S2, PT="10s"):
        t.ALARM = True  # S ALARM


def acknowledge(t):
    """Rung 4: ACK resets ALARM."""
    if t.ACK:
        t.ALARM = False  # R ALARM


OB1 = [start_belt, stop_belt, watchdog, acknowledge]
