"""Wrong (a typical slip, not from the textbook): "count reached" compared with > instead of >=.

OBJEKT_PRI_OS2 := M1_AKTUALNY_POCET > M1_ZIADANY_POCET comes one move late: every object makes one move
to OS2 more than required.
"""


def loading(t):
    """Fig. 6.30: as 6.3.1 rung 1."""
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
    """Fig. 6.32 with > for >=."""
    if N(t.OS2, "POM_N_OS2"):
        t.M1_AKTUALNY_POCET = t.M1_AKTUALNY_POCET + 1  # ADD
    t.OBJEKT_PRI_OS2 = t.M1_AKTUALNY_POCET > t.M1_ZIADANY_POCET


def removal(t):
    """Fig. 6.33: -|P|- OS1 AND NOT M1_VPRED AND NOT M1_VZAD -> MOVE 0."""
    if P(t.OS1, "POM_P_OS1") and not t.M1_VPRED and not t.M1_VZAD:
        t.M1_AKTUALNY_POCET = 0  # MOVE


OB1 = [loading, end_of_belt, counting, removal]
