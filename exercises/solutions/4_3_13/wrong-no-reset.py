"""A typical slip (not from the textbook): the counter is never reset.

The first sequence is right, but STROJ_KONIEC stays TRUE after STROJ_START is withdrawn, so a new
STROJ_START never runs the machine again.
"""

TON_S = IEC_TIMER()
CTU_S = IEC_COUNTER()


def cycle(t):
    q = t.TON_S.TON(IN=t.STROJ_START and not t.STROJ_KONIEC, PT="3s")
    t.STROJ_KONIEC = t.CTU_S.CTU(CU=q, R=False, PV=3)
    if q:
        RT(t.TON_S)


def machine(t):
    t.STROJ_ZAP = t.STROJ_START and not t.STROJ_KONIEC and t.TON_S.ET < TIME("1s")


OB1 = [cycle, machine]
