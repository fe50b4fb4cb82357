"""A typical slip (not from the textbook): the counter in its own network after the RT.

Network 1 resets the timer (RT) in its expiry scan; network 2 reads TON_S.Q for the counter's CU.
On an S7-1200 that read sees the instance already reset (Q = FALSE), so the counter never counts,
STROJ_KONIEC never comes and the machine goes on cycling for ever.
"""

TON_S = IEC_TIMER()
CTU_S = IEC_COUNTER()


def cycle(t):
    if t.TON_S.TON(IN=t.STROJ_START and not t.STROJ_KONIEC, PT="3s"):
        RT(t.TON_S)


def count(t):
    t.STROJ_KONIEC = t.CTU_S.CTU(CU=t.TON_S.Q, R=not t.STROJ_START, PV=3)


def machine(t):
    t.STROJ_ZAP = t.STROJ_START and not t.STROJ_KONIEC and t.TON_S.ET < TIME("1s")


OB1 = [cycle, count, machine]
