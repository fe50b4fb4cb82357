"""6.3.2, solution 1 (textbook Figs. 6.28-6.29): the required number of moves to OS2 counted by a CTU.

The counter's CU is "object at OS2" (NOT OS2, NC barrier), its PV the parameter M1_ZIADANY_POCET; its QU
blocks a new start at OS1 as OBJEKT_PRI_OS2 did in 6.3.1. The removal (rising edge of OS1 with the belt
standing) resets it. M1_AKTUALNY_POCET := CV is stored "for demonstration".
"""

CTU_M1 = IEC_COUNTER()


def loading(t):
    """Fig. 6.28: object at OS1 -> S M1_VPRED unless the count is reached (upper branch); R M1_VZAD (lower)."""
    if not t.OS1:
        if not t.CTU_M1.QU:
            t.M1_VPRED = True  # S
        t.M1_VZAD = False  # R


def counting(t):
    """Fig. 6.29: CTU (CU := object at OS2, R := removal, PV := M1_ZIADANY_POCET); at OS2 reverse."""
    removal = P(t.OS1, "POM_P_OS1") and not t.M1_VPRED and not t.M1_VZAD
    t.CTU_M1.CTU(CU=not t.OS2, R=removal, PV=t.M1_ZIADANY_POCET)
    t.M1_AKTUALNY_POCET = t.CTU_M1.CV
    if not t.OS2:
        t.M1_VPRED = False  # R
        t.M1_VZAD = True  # S


OB1 = [loading, counting]
