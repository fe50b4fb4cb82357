"""4.3.7, version 1 (textbook Figs. 4.76-4.78): the watchdog stops the belt and sets ALARM, but nothing resets it.

The TON's Q output "assigns TRUE to ALARM and FALSE to D1" in one rung. The textbook stresses that Q is
TRUE for one scan only: in the next scan D1 is FALSE, IN is FALSE and the timer resets; ALARM is a SET
coil, so it stays. Version 1 has no acknowledgement yet: once raised, ALARM can never be cleared
(version 2 adds the ACK rung). Shipped as "wrong" for that reason.
"""

TON_A = IEC_TIMER()


def start_belt(t):
    """Rung 1: an object at S1 sets D1."""
    if t.S1:
        t.D1 = True  # S D1


def stop_belt(t):
    """Rung 2: the object at S2 resets D1."""
    if t.S2:
        t.D1 = False  # R D1


def watchdog(t):
    """Rung 3: TON_A(IN := D1 AND NOT S2, PT := 10 s); Q -> S ALARM, R D1."""
    if t.TON_A.TON(IN=t.D1 and not t.S2, PT="10s"):
        t.ALARM = True  # S ALARM
        t.D1 = False  # R D1


OB1 = [start_belt, stop_belt, watchdog]
