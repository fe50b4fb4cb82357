"""Wrong (the textbook argues against it): OBJEKT_PRI_OS2 in front of both branches of rung 1.

"The auxiliary bit is only in the upper branch because in the lower branch the detection must stop the
motion": here the returning object, which has been at OS2, no longer resets M1_VZAD at OS1; the belt
runs on backward and the object falls off the loading end.
"""


def loading(t):
    """Object at OS1 and not yet at OS2 -> S M1_VPRED, R M1_VZAD (the stop of the return is lost)."""
    if not t.OS1 and not t.OBJEKT_PRI_OS2:
        t.M1_VPRED = True  # S
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
