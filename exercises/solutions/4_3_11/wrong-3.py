"""4.3.11, solution 3, "not quite correct" (textbook): the timer input is NOT Takt1s.

In the expiry scan Takt1s is TRUE (as in solution 2). In the next scan IN = NOT Takt1s = FALSE, so
the timer is reset again and FALSE is written to Takt1s; only in the scan after that does the timer
really start. One extra scan per period: 1 s + 2 scans. Negligible at a 1 ms cycle, but at a 100 ms
cycle the clock is off by up to 10 % (1.2 s instead of solution 2's 1.1 s).
"""

TON_T = IEC_TIMER()


def OB1(t):
    q = t.TON_T.TON(IN=not t.Takt1s, PT="1s")
    t.Takt1s = q
    if q:
        RT(t.TON_T)
