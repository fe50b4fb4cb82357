"""Wrong (a typical slip, not from the textbook): the press is never stopped at KS1.

Without "IF KS1 THEN R M2_HORE" the press runs up past the upper limit switch into its end stop, where
the motor stalls; the next object then finds M2_HORE still on when M2_DOLE is set.
"""


def start_stroke(t):
    """Object at OS2 AND KS1 AND NOT OBJEKT_BOL_DOLE -> S M2_DOLE (the R M2_HORE at KS1 is missing)."""
    if not t.OS2 and t.KS1 and not t.OBJEKT_BOL_DOLE:
        t.M2_DOLE = True  # S


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
