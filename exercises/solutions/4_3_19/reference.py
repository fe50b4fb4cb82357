"""4.3.19, the textbook's program (Fig. 4.176) in OB30: TL -> S LED, every 1 s.

OB30 reads TL only when it runs (0 s, 1 s, 2 s ...): the LED is set at the first call that sees the
button pressed and stays set; a press that starts and ends between two calls is never seen.
"""


def set_led(t):
    if t.TL:
        t.LED = True  # S LED


OB30 = CyclicInterrupt(set_led, period="1s")
