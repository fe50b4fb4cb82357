"""Wrong (a typical slip, not from the textbook): the stroke starts without the OBJEKT_BOL_DOLE test.

Nothing remembers that the press has been down: back at KS1 with the object still at OS2, the press goes
down again, and again, until the object is taken away. The task allows one stroke per object.
"""


def start_stroke(t):
    """Object at OS2 AND KS1 -> S M2_DOLE (NOT OBJEKT_BOL_DOLE missing); at KS1 -> R M2_HORE."""
    if not t.OS2 and t.KS1:
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
    """Fig. 6.36: -|P|- OS2 -> R OBJEKT_BOL_DOLE."""
    if P(t.OS2, "POM_P_OS2"):
        t.OBJEKT_BOL_DOLE = False  # R


OB1 = [start_stroke, bottom, removal]
