"""4.3.8, the textbook's alternative (Fig. 4.86): the LED follows the comparison ET > 500 ms directly.

TON_B(IN := ALARM, PT := 1 s) is restarted by RT every 1 s. LED := TON_B.ET > 500 ms. When ALARM is
cleared the timer resets, ET = 0 ms, the comparison is FALSE and the LED goes out.

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


def alarm_lamp(t):
    """Rung 6: LED := TON_B.ET > 500 ms."""
    t.LED = t.TON_B.ET > TIME("500ms")


OB1 = [start_belt, watchdog, stop_belt, acknowledge, blink_timer, alarm_lamp]
