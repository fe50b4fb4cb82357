"""6.3.3 (textbook Figs. 6.34-6.36): one press stroke, down and up, for each object put at OS2.

"Similar to task 1, except that the object does not move; the punching part of the model moves." KS1 is
the upper limit switch, KS2 the lower one (as all the textbook's solutions use them). OBJEKT_BOL_DOLE
("the press has been down for this object") lets the stroke start only once per object; the object's
removal, the rising edge of the NC input OS2, clears it.
"""


def start_stroke(t):
    """Fig. 6.34: object at OS2 AND KS1 AND NOT OBJEKT_BOL_DOLE -> S M2_DOLE; at KS1 -> R M2_HORE."""
    if not t.OS2 and t.KS1 and not t.OBJEKT_BOL_DOLE:
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
