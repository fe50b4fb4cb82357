"""6.3.3 without the KS1 interlock (a slip, not from the textbook): the stroke starts for an object at OS2 that the
press has not been down for, whether or not the press is at the top.

One object at a time, put there while the press waits at KS1, it behaves as the reference. An object exchanged
while the ram goes back up (the removal has cleared OBJEKT_BOL_DOLE) starts the stroke at once: M2_DOLE is set while
M2_HORE still drives the press up, both directions at once.
"""


def start_stroke(t):
    """Fig. 6.34 without KS1: object at OS2 AND NOT OBJEKT_BOL_DOLE -> S M2_DOLE; at KS1 -> R M2_HORE."""
    if not t.OS2 and not t.OBJEKT_BOL_DOLE:
        t.M2_DOLE = True  # S
    if t.KS1:
        t.M2_HORE = False  # R


def bottom(t):
    """Fig. 6.35: at KS2 -> R M2_DOLE, S M2_HORE, S OBJEKT_BOL_DOLE."""
    if t.KS2:
        t.M2_DOLE = False  # R
        t.M2_HORE = True  # S
        t.OBJEKT_BOL_DOLE = True  # S


def removal(t):
    """Fig. 6.36: -|P|- OS2 (the object taken away) -> R OBJEKT_BOL_DOLE."""
    if P(t.OS2, "POM_P_OS2"):
        t.OBJEKT_BOL_DOLE = False  # R


OB1 = [start_stroke, bottom, removal]
