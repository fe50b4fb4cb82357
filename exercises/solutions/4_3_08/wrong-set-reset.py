"""Wrong: solution 2 with ALARM in both LED rungs (SET and RESET coils), the LED can stay lit after ACK.

The catalogue's reading of Fig. 4.85: IF ALARM AND ET <= 500 ms THEN R LED; IF ALARM AND ET > 500 ms
THEN S LED. While ALARM is TRUE it blinks like the alternative. But a SET/RESET coil keeps its value
when its rung is FALSE: once ACK clears ALARM neither rung executes, and if the LED was lit at that
moment it stays lit for good. The textbook's alternative (LED := ET > 500 ms) avoids this.

The first four networks are the alarm of 4.3.7 (version 3).
"""

TON_A = IEC_TIMER()
TON_B = IEC_TIMER()


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


def blink_timer(t):
    """Rung 5: TON_B(IN := ALARM, PT := 1 s); Q -> RT TON_B."""
    if t.TON_B.TON(IN=t.ALARM, PT="1s"):
        RT(t.TON_B)


def lamp_off(t):
    """Rung 6: ALARM AND ET <= 500 ms -> R LED."""
    if t.ALARM and t.TON_B.ET <= TIME("500ms"):
        t.LED = False  # R LED


def lamp_on(t):
    """Rung 7: ALARM AND ET > 500 ms -> S LED."""
    if t.ALARM and t.TON_B.ET > TIME("500ms"):
        t.LED = True  # S LED


OB1 = [start_belt, watchdog, stop_belt, acknowledge, blink_timer, lamp_off, lamp_on]
