"""Wrong for this model (the textbook's own contradiction): a program that reads the model text literally.

The model text names the press's "lower and upper positions ... KS1 and KS2", i.e. KS1 lower and KS2
upper; all the textbook's solutions use KS1 as the upper switch, and so is the model wired here. Written
for the text's reading, the program takes KS1, actuated while the press waits at the top, for "the press
is down": it drives the press up into its upper end stop and never punches an object. (On the rig built
with ks1="lower" it is the correct program.)
"""


def start_stroke(t):
    """Object at OS2 AND KS2 (read as the upper switch) AND NOT OBJEKT_BOL_DOLE -> S M2_DOLE."""
    if not t.OS2 and t.KS2 and not t.OBJEKT_BOL_DOLE:
        t.M2_DOLE = True  # S
    if t.KS2:
        t.M2_HORE = False  # R


def bottom(t):
    """At KS1 (read as the lower switch) -> R M2_DOLE, S M2_HORE, S OBJEKT_BOL_DOLE."""
    if t.KS1:
        t.M2_DOLE = False  # R
        t.M2_HORE = True  # S
        t.OBJEKT_BOL_DOLE = True  # S


def removal(t):
    """Fig. 6.36: -|P|- OS2 -> R OBJEKT_BOL_DOLE."""
    if P(t.OS2, "POM_P_OS2"):
        t.OBJEKT_BOL_DOLE = False  # R


OB1 = [start_stroke, bottom, removal]
