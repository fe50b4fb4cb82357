"""6.3.2, solution 2 (textbook Figs. 6.30-6.33): the moves to OS2 counted with ADD.

Each arrival at OS2 (the falling edge of the NC input) adds 1 to M1_AKTUALNY_POCET; OBJEKT_PRI_OS2 now
means "the required count is reached" and blocks a new start at OS1, as in 6.3.1. The removal at OS1
(rising edge with the belt standing) moves 0 into the count, which clears OBJEKT_PRI_OS2.
"""


def loading(t):
    """Fig. 6.30: as 6.3.1 rung 1 (start forward unless OBJEKT_PRI_OS2; stop the return at OS1)."""
    if not t.OS1:
        if not t.OBJEKT_PRI_OS2:
            t.M1_VPRED = True  # S
        t.M1_VZAD = False  # R


def end_of_belt(t):
    """Fig. 6.31: object at OS2 -> R M1_VPRED, S M1_VZAD."""
    if not t.OS2:
        t.M1_VPRED = False  # R
        t.M1_VZAD = True  # S


def counting(t):
    """Fig. 6.32: -|N|- OS2 -> ADD 1 (executed once per arrival); below: OBJEKT_PRI_OS2 := count reached."""
    if N(t.OS2, "POM_N_OS2"):
        t.M1_AKTUALNY_POCET = t.M1_AKTUALNY_POCET + 1  # ADD
    t.OBJEKT_PRI_OS2 = t.M1_AKTUALNY_POCET >= t.M1_ZIADANY_POCET


def removal(t):
    """Fig. 6.33: -|P|- OS1 AND NOT M1_VPRED AND NOT M1_VZAD -> MOVE 0 -> M1_AKTUALNY_POCET."""
    if P(t.OS1, "POM_P_OS1") and not t.M1_VPRED and not t.M1_VZAD:
        t.M1_AKTUALNY_POCET = 0  # MOVE


OB1 = [loading, end_of_belt, counting, removal]
