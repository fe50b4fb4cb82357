"""Wrong (a typical slip, not from the textbook): M1_VPRED as a coil instead of a SET.

M1_VPRED := present(OS1) AND NOT OBJEKT_PRI_OS2 holds the belt on only while OS1 sees the object: it
stops as soon as the object has left the beam, a few millimetres after the start, and never gets to
OS2.
"""


def loading(t):
    """Coil: the belt runs forward only while the object is inside the OS1 beam."""
    t.M1_VPRED = not t.OS1 and not t.OBJEKT_PRI_OS2
    if not t.OS1:
        t.M1_VZAD = False  # R


def end_of_belt(t):
    """Fig. 6.26: object at OS2 -> R M1_VPRED, S M1_VZAD, S OBJEKT_PRI_OS2."""
    if not t.OS2:
        t.M1_VPRED = False  # R
        t.M1_VZAD = True  # S
        t.OBJEKT_PRI_OS2 = True  # S


def removal(t):
    """Fig. 6.27: -|P|- OS1 AND NOT M1_VPRED AND NOT M1_VZAD -> R OBJEKT_PRI_OS2."""
    if P(t.OS1, "POM_P_OS1") and not t.M1_VPRED and not t.M1_VZAD:
        t.OBJEKT_PRI_OS2 = False  # R


OB1 = [loading, end_of_belt, removal]
