"""6.3.4 (textbook Figs. 6.37-6.43): task 3 integrated into task 2 (solution 2).

Rungs 1-4 are 6.3.2's solution 2 (the moves to OS2 counted with ADD), rungs 5-7 are 6.3.3 (one press
stroke). The connection is in rung 2: the object detected at OS2 must not be sent back before the punching
is finished, so the reverse needs "the press has been down (OBJEKT_BOL_DOLE) AND is back at the top
(KS1)"; without KS1 the object would start moving during the punching. OBJEKT_BOL_DOLE is cleared when the
object leaves OS2 on its way back (rising edge of OS2), so that each visit gets its own stroke.
"""


def loading(t):
    """Fig. 6.37: object at OS1 -> S M1_VPRED unless OBJEKT_PRI_OS2 (upper branch); R M1_VZAD (lower)."""
    if not t.OS1:
        if not t.OBJEKT_PRI_OS2:
            t.M1_VPRED = True  # S
        t.M1_VZAD = False  # R


def end_of_belt(t):
    """Fig. 6.38: object at OS2 -> R M1_VPRED; AND OBJEKT_BOL_DOLE AND KS1 -> S M1_VZAD."""
    if not t.OS2:
        t.M1_VPRED = False  # R
        if t.OBJEKT_BOL_DOLE and t.KS1:
            t.M1_VZAD = True  # S


def counting(t):
    """Fig. 6.39: -|N|- OS2 -> ADD 1; OBJEKT_PRI_OS2 := M1_AKTUALNY_POCET >= M1_ZIADANY_POCET."""
    if N(t.OS2, "POM_N_OS2"):
        t.M1_AKTUALNY_POCET = t.M1_AKTUALNY_POCET + 1  # ADD
    t.OBJEKT_PRI_OS2 = t.M1_AKTUALNY_POCET >= t.M1_ZIADANY_POCET


def removal(t):
    """Fig. 6.40: -|P|- OS1 AND NOT M1_VPRED AND NOT M1_VZAD -> MOVE 0 -> M1_AKTUALNY_POCET."""
    if P(t.OS1, "POM_P_OS1") and not t.M1_VPRED and not t.M1_VZAD:
        t.M1_AKTUALNY_POCET = 0  # MOVE


def start_stroke(t):
    """Fig. 6.41: object at OS2 AND KS1 AND NOT OBJEKT_BOL_DOLE -> S M2_DOLE; at KS1 -> R M2_HORE."""
    if not t.OS2 and t.KS1 and not t.OBJEKT_BOL_DOLE:
        t.M2_DOLE = True  # S
    if t.KS1:
        t.M2_HORE = False  # R


def bottom(t):
    """Fig. 6.42: at KS2 -> R M2_DOLE, S M2_HORE, S OBJEKT_BOL_DOLE."""
    if t.KS2:
        t.M2_DOLE = False  # R
        t.M2_HORE = True  # S
        t.OBJEKT_BOL_DOLE = True  # S


def leaving(t):
    """Fig. 6.43: -|P|- OS2 (the object left the press) -> R OBJEKT_BOL_DOLE."""
    if P(t.OS2, "POM_P_OS2"):
        t.OBJEKT_BOL_DOLE = False  # R


OB1 = [loading, end_of_belt, counting, removal, start_stroke, bottom, leaving]
