"""4.3.7, version 2 (textbook Fig. 4.79): the alarm only indicates; it does not block the belt.

Two changes to version 1: the timer's Q is moved into the reset rung (S2 OR TON_A.Q resets D1) and
an acknowledgement rung is added (ACK resets ALARM). A new object at S1 restarts the belt even while
ALARM is TRUE, so this version is not graded on the scenario "new object during the alarm" (that is
version 3's behaviour).

Rung order [R]: the TON box runs before the reset rung reads TON_A.Q (see wrong-scan-order.py).
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
    """Rung 3: S2 OR TON_A.Q resets D1."""
    if t.S2 or t.TON_A.Q:
        t.D1 = False  # R D1


def acknowledge(t):
    """Rung 4: ACK resets ALARM."""
    if t.ACK:
        t.ALARM = False  # R ALARM


OB1 = [start_belt, watchdog, stop_belt, acknowledge]
