"""Wrong (from the textbook's wording, not one of its solutions): "blink with a period of 0.5 s" taken literally.

The task says "with a period of 0.5 s (i.e. 0.5 s TRUE, 0.5 s FALSE)"; the parenthesis (and the
textbook's own use of Clock_1Hz) means a half-period of 0.5 s. A student who takes "period 0.5 s" at
its word picks Clock_2Hz (%M0.3, period 0.5 s): the LED is on for 0.25 s and off for 0.25 s. The duty
cycle is still 50 %; only the phase lengths give it away.

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


def alarm_lamp(t):
    """Rung 5: LED := ALARM AND Clock_2Hz."""
    t.LED = t.ALARM and t.Clock_2Hz


OB1 = [start_belt, watchdog, stop_belt, acknowledge, alarm_lamp]
