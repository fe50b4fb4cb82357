"""Wrong (a typical slip, not from the textbook): the LED set and reset on Clock_1Hz instead of assigned.

IF ALARM AND Clock_1Hz THEN S LED; IF ALARM AND NOT Clock_1Hz THEN R LED. While ALARM is TRUE it
blinks exactly like solution 1. But SET and RESET coils keep their value when their rung is FALSE:
once ACK clears ALARM neither rung executes, and if the acknowledgement came while Clock_1Hz was
TRUE the LED stays lit for good.

The first four networks are the alarm of 4.3.7 (version 3).
"""

TON_A = IEC_TIMER()


def start_belt(t):
    """4.3.7 rung 1: an object at S1 sets D1."""
    if t.S1:
        t.D1 = True  # S D1


def watchdog(t):
    """4.3.7 rung 2: TON_A(IN := D1 AND NOT S2, PT := 10 s); its Q sets ALARM."""
    if t.TON_A.TON(IN=t.D1 and not t.S2, PT="10s"):
        t.ALARM = True  # S ALARM


def stop_belt(t):
    """4.3.7 rung 3: S2 OR TON_A.Q OR ALARM resets D1."""
    if t.S2 or t.TON_A.Q or t.ALARM:
        t.D1 = False  # R D1


def acknowledge(t):
    """4.3.7 rung 4: ACK resets ALARM."""
    if t.ACK:
        t.ALARM = False  # R ALARM


def lamp_on(t):
    """Rung 5: ALARM AND Clock_1Hz -> S LED."""
    if t.ALARM and t.Clock_1Hz:
        t.LED = True  # S LED


def lamp_off(t):
    """Rung 6: ALARM AND NOT Clock_1Hz -> R LED."""
    if t.ALARM and not t.Clock_1Hz:
        t.LED = False  # R LED


OB1 = [start_belt, watchdog, stop_belt, acknowledge, lamp_on, lamp_off]
