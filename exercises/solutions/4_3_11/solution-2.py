"""4.3.11, solution 2: a self-restarting timer, IN = AlwaysTRUE, reset by RT when it expires.

In the expiry scan Takt1s is TRUE and RT resets the timer; in the next scan IN is TRUE and the timer
(reset in the previous scan) starts again with Q = FALSE, so Takt1s goes FALSE. Period 1 s + 1 scan.
"""

TON_T = IEC_TIMER()


def OB1(t):
    q = t.TON_T.TON(IN=t.AlwaysTRUE, PT="1s")
    t.Takt1s = q
    if q:
        RT(t.TON_T)
