"""Wrong (a typical slip, not from the textbook): the NC light barriers read as if they were NO.

OS1 and OS2 are TRUE while their beam is free. A program that takes TRUE for "object present" sees an
object at OS1 and at OS2 as soon as the CPU starts: the belt is sent backward with nothing on it, and a
real object placed at OS1 is carried off the loading end.
"""


def loading(t):
    """OS1 TRUE taken for "object at OS1"."""
    if t.OS1:
        if not t.OBJEKT_PRI_OS2:
            t.M1_VPRED = True  # S
        t.M1_VZAD = False  # R


def end_of_belt(t):
    """OS2 TRUE taken for "object at OS2"."""
    if t.OS2:
        t.M1_VPRED = False  # R
        t.M1_VZAD = True  # S
        t.OBJEKT_PRI_OS2 = True  # S


def removal(t):
    """Falling edge taken for the removal."""
    if N(t.OS1, "POM_P_OS1") and not t.M1_VPRED and not t.M1_VZAD:
        t.OBJEKT_PRI_OS2 = False  # R


OB1 = [loading, end_of_belt, removal]
