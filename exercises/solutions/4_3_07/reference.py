"""4.3.7, version 3 (textbook Fig. 4.80): the 10 s transport watchdog raises ALARM and blocks the belt.

TON_A times while the belt runs without an object at S2. If S2 is not reached within 10 s, the timer's
Q sets ALARM, and the reset rung stops D1: through TON_A.Q in the expiry scan and through ALARM in
every scan after it, so the belt stays off until the operator acknowledges (ACK resets ALARM) and an
object at S1 starts it again.

Rung order [R, the figure is missing]: the TON box runs before the reset rung reads TON_A.Q. The
other order is the scan-order trap of wrong-scan-order.py.
"""

TON_A = IEC_TIMER()


def start_belt(t):
    """Rung 1: an object at S1 sets D1."""
    if t.S1:
        t.D1 = True  # S D1


def watchdog(t):
    """Rung 2: TON_A(IN := D1 AND NOT S2, PT := 10 s); its Q sets ALARM."""
    if t.TON_A.TON(IN=t.D1 and not t.S2, PT="10s"):
        t.ALARM = True  # S ALARM


def stop_belt(t):
    """Rung 3: S2 OR TON_A.Q OR ALARM resets D1 (every scan while ALARM is TRUE)."""
    if t.S2 or t.TON_A.Q or t.ALARM:
        t.D1 = False  # R D1


def acknowledge(t):
    """Rung 4: ACK resets ALARM."""
    if t.ACK:
        t.ALARM = False  # R ALARM


OB1 = [start_belt, watchdog, stop_belt, acknowledge]
