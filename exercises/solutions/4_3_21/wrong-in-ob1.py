"""The textbook's comparison (4.3.21): the same timer network in OB1 instead of OB30.

In the program cycle (every millisecond) pressing and holding the button starts the timer and the
SET runs 100 ms later (+- 2 ms). That is the "precise" behaviour the exercise contrasts with OB30; as
an answer to this exercise (the program in OB30) it is wrong: the LED does not wait for the calls.
"""

TON_L = IEC_TIMER()


def delayed_led(t):
    if t.TON_L.TON(IN=t.TL, PT="100ms"):
        t.LED = True  # S LED


OB1 = [delayed_led]
