"""4.3.21, the textbook's program (Fig. 4.183) in OB30: TON_L (IN = TL, PT = 100 ms), Q -> S LED.

The timer is only looked at once a second: the call that first sees TL starts it, the next call
(1 s later, ET = 1 s > 100 ms) sets the LED, provided TL is still pressed then. Timers in a periodic
task with a long period are unsuitable for precise timing.
"""

TON_L = IEC_TIMER()


def delayed_led(t):
    if t.TON_L.TON(IN=t.TL, PT="100ms"):
        t.LED = True  # S LED


OB30 = CyclicInterrupt(delayed_led, period="1s")
