"""Wrong (a typical slip, not from the textbook): solution 2's ADD without the edge instruction.

ADD runs in every scan in which OS2 sees the object, so one arrival adds as many as there are scans
until the belt has carried the object out of the beam again: the count overshoots the parameter at the
first visit and the object comes back after one move, whatever M1_ZIADANY_POCET says.
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
    """ADD 1 in every scan that sees the object at OS2 (the -|N|- is missing)."""
    if not t.OS2:
        t.M1_AKTUALNY_POCET = t.M1_AKTUALNY_POCET + 1  # ADD
    t.OBJEKT_PRI_OS2 = t.M1_AKTUALNY_POCET >= t.M1_ZIADANY_POCET


def removal(t):
    """Fig. 6.33: -|P|- OS1 AND NOT M1_VPRED AND NOT M1_VZAD -> MOVE 0."""
    if P(t.OS1, "POM_P_OS1") and not t.M1_VPRED and not t.M1_VZAD:
        t.M1_AKTUALNY_POCET = 0  # MOVE


OB1 = [loading, end_of_belt, counting, removal]
