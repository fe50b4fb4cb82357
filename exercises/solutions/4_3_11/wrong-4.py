"""4.3.11, solution 4, wrong (textbook, Fig. 4.107): the timer input is the negated timer output.

On an S7-1200 every read of Q or ET refreshes the instance. In the scan in which ET reaches PT, the
NC contact on TON_T.Q reads the instance *before* the TON box runs: the refresh makes Q TRUE, the
contact passes FALSE to IN, which resets the timer, and Q is FALSE again at the box. TRUE is never
written to Takt1s and RT never runs; the timer silently restarts about every second.
"""

TON_T = IEC_TIMER()


def OB1(t):
    q = t.TON_T.TON(IN=not t.TON_T.Q, PT="1s")
    t.Takt1s = q
    if q:
        RT(t.TON_T)
