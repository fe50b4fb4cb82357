"""6.3.1 (textbook Figs. 6.25-6.27): carry the object from OS1 to OS2, bring it back to OS1 and wait there.

OS1 and OS2 are NC light barriers: the input is TRUE while the beam is free, so "object present" is
NOT OS1. OBJEKT_PRI_OS2 remembers that the object has been at OS2. It is only in the upper branch of
rung 1: in the lower branch the returning object must stop the motion (the textbook's point). The
object's removal is the rising edge of OS1 with the belt standing: the object also leaves OS1 when it
starts moving forward, which must not count.
"""


def loading(t):
    """Fig. 6.25: object at OS1 -> S M1_VPRED unless it has been at OS2 (upper branch); R M1_VZAD (lower)."""
    if not t.OS1:
        if not t.OBJEKT_PRI_OS2:
            t.M1_VPRED = True  # S
        t.M1_VZAD = False  # R


def end_of_belt(t):
    """Fig. 6.26: object at OS2 -> R M1_VPRED, S M1_VZAD, S OBJEKT_PRI_OS2."""
    if not t.OS2:
        t.M1_VPRED = False  # R
        t.M1_VZAD = True  # S
        t.OBJEKT_PRI_OS2 = True  # S


def removal(t):
    """Fig. 6.27: -|P|- OS1 AND NOT M1_VPRED AND NOT M1_VZAD -> R OBJEKT_PRI_OS2 (taken away, belt standing)."""
    if P(t.OS1, "POM_P_OS1") and not t.M1_VPRED and not t.M1_VZAD:
        t.OBJEKT_PRI_OS2 = False  # R


OB1 = [loading, end_of_belt, removal]
