"""Wrong (a typical slip, not from the textbook): rung 2 sets M1_VZAD but forgets to reset M1_VPRED.

At OS2 both relays of M1 are on: a short circuit in a real relay H-bridge. The model's motor stops (the
two directions cancel) and the object stays at OS2.
"""


def loading(t):
    """Fig. 6.25: object at OS1 -> S M1_VPRED unless it has been at OS2; R M1_VZAD."""
    if not t.OS1:
        if not t.OBJEKT_PRI_OS2:
            t.M1_VPRED = True  # S
        t.M1_VZAD = False  # R


def end_of_belt(t):
    """Object at OS2 -> S M1_VZAD, S OBJEKT_PRI_OS2 (the R M1_VPRED is missing)."""
    if not t.OS2:
        t.M1_VZAD = True  # S
        t.OBJEKT_PRI_OS2 = True  # S


def removal(t):
    """Fig. 6.27: -|P|- OS1 AND NOT M1_VPRED AND NOT M1_VZAD -> R OBJEKT_PRI_OS2."""
    if P(t.OS1, "POM_P_OS1") and not t.M1_VPRED and not t.M1_VZAD:
        t.OBJEKT_PRI_OS2 = False  # R


OB1 = [loading, end_of_belt, removal]
