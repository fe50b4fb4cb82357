"""4.3.13, solution 1 as the textbook's solution text describes it: OFF for 1 s, then ON for 2 s.

The text says "in the interval 0 ms ... 1 s the output is FALSE and in 1 s ... 3 s TRUE, i.e. the
machine is off 1 s and on 2 s" (and names STROJ_START where STROJ_ZAP is meant). That is ET >= 1 s,
the opposite of the task ("on lasts 1 s, off lasts 2 s"). Graded against the task, which is
normative, the ON and OFF phases have swapped lengths and the machine starts 1 s late.
"""

TON_S = IEC_TIMER()
CTU_S = IEC_COUNTER()


def cycle(t):
    q = t.TON_S.TON(IN=t.STROJ_START and not t.STROJ_KONIEC, PT="3s")
    t.STROJ_KONIEC = t.CTU_S.CTU(CU=q, R=not t.STROJ_START, PV=3)
    if q:
        RT(t.TON_S)


def machine(t):
    t.STROJ_ZAP = t.STROJ_START and not t.STROJ_KONIEC and t.TON_S.ET >= TIME("1s")


OB1 = [cycle, machine]
