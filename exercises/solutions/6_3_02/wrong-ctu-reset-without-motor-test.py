"""Wrong (the textbook argues against it): solution 1 with the counter reset on every rising edge of OS1.

R := P(OS1) alone resets the CTU each time the object sets off from OS1 towards OS2, not only when it is
taken away with the belt standing: with two or more required moves QU never comes and the object shuttles
without end.
"""

CTU_M1 = IEC_COUNTER()


def loading(t):
    """Fig. 6.28: object at OS1 -> S M1_VPRED unless QU; R M1_VZAD."""
    if not t.OS1:
        if not t.CTU_M1.QU:
            t.M1_VPRED = True  # S
        t.M1_VZAD = False  # R


def counting(t):
    """CTU with R := P(OS1), the belt-standing test left out; at OS2 reverse."""
    t.CTU_M1.CTU(CU=not t.OS2, R=P(t.OS1, "POM_P_OS1"), PV=t.M1_ZIADANY_POCET)
    t.M1_AKTUALNY_POCET = t.CTU_M1.CV
    if not t.OS2:
        t.M1_VPRED = False  # R
        t.M1_VZAD = True  # S


OB1 = [loading, counting]
