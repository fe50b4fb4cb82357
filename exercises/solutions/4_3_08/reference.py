"""4.3.8, solution 1 (textbook): the CPU's clock memory blinks the LED.

Clock memory is enabled at MB0 in the CPU configuration (the exercise's hardware configuration;
system memory at MB1), so Clock_1Hz (%M0.5) changes every 0.5 s. The LED is lit while ALARM is TRUE
and Clock_1Hz is TRUE: 0.5 s on, 0.5 s off, and dark as soon as ALARM is cleared.

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
    """Rung 5: LED := ALARM AND Clock_1Hz."""
    t.LED = t.ALARM and t.Clock_1Hz


OB1 = [start_belt, watchdog, stop_belt, acknowledge, alarm_lamp]
