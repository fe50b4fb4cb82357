"""6.3.5 (a slip): the next stroke started by the ram coming back to KS1, not by the object at OS2.

Rung 5 reads "start down for an object at OS2, or when the press comes back up (M2_HORE still on at KS1),
until the strokes are done": while the object stays under the press it is the textbook's sequence, stroke for
stroke. Taken away between two strokes (the count is cleared as it leaves OS2), the press comes back up and
goes down again on the empty place, and again, for ever.
"""


def loading(t):
    """Fig. 6.44 (as 6.3.4): object at OS1 -> S M1_VPRED unless OBJEKT_PRI_OS2 (upper branch); R M1_VZAD (lower)."""
    if not t.OS1:
        if not t.OBJEKT_PRI_OS2:
            t.M1_VPRED = True  # S
        t.M1_VZAD = False  # R


def end_of_belt(t):
    """Fig. 6.45 (as 6.3.4): object at OS2 -> R M1_VPRED; AND OBJEKT_BOL_DOLE AND KS1 -> S M1_VZAD."""
    if not t.OS2:
        t.M1_VPRED = False  # R
        if t.OBJEKT_BOL_DOLE and t.KS1:
            t.M1_VZAD = True  # S


def counting(t):
    """Fig. 6.46 (as 6.3.4): -|N|- OS2 -> ADD 1; OBJEKT_PRI_OS2 := M1_AKTUALNY_POCET >= M1_ZIADANY_POCET."""
    if N(t.OS2, "POM_N_OS2"):
        t.M1_AKTUALNY_POCET = t.M1_AKTUALNY_POCET + 1  # ADD
    t.OBJEKT_PRI_OS2 = t.M1_AKTUALNY_POCET >= t.M1_ZIADANY_POCET


def removal(t):
    """Fig. 6.47 (as 6.3.4): -|P|- OS1 AND NOT M1_VPRED AND NOT M1_VZAD -> MOVE 0 -> M1_AKTUALNY_POCET."""
    if P(t.OS1, "POM_P_OS1") and not t.M1_VPRED and not t.M1_VZAD:
        t.M1_AKTUALNY_POCET = 0  # MOVE


def start_stroke(t):
    """Fig. 6.48 with the repeat stroke on the ram's return: (object at OS2 OR M2_HORE) AND KS1 AND NOT
    OBJEKT_BOL_DOLE -> S M2_DOLE; at KS1 -> R M2_HORE."""
    if (not t.OS2 or t.M2_HORE) and t.KS1 and not t.OBJEKT_BOL_DOLE:
        t.M2_DOLE = True  # S
    if t.KS1:
        t.M2_HORE = False  # R


def bottom(t):
    """Fig. 6.49: -|P|- KS2 -> ADD 1 to M2_AKTUALNY_POCET; at KS2 -> R M2_DOLE, S M2_HORE."""
    if P(t.KS2, "POM_P_KS2"):
        t.M2_AKTUALNY_POCET = t.M2_AKTUALNY_POCET + 1  # ADD
    if t.KS2:
        t.M2_DOLE = False  # R
        t.M2_HORE = True  # S


def strokes_done(t):
    """Fig. 6.50: OBJEKT_BOL_DOLE := M2_AKTUALNY_POCET >= M2_ZIADANY_POCET."""
    t.OBJEKT_BOL_DOLE = t.M2_AKTUALNY_POCET >= t.M2_ZIADANY_POCET


def leaving(t):
    """Fig. 6.51: -|P|- OS2 (the object left the press) -> MOVE 0 -> M2_AKTUALNY_POCET."""
    if P(t.OS2, "POM_P_OS2"):
        t.M2_AKTUALNY_POCET = 0  # MOVE


OB1 = [loading, end_of_belt, counting, removal, start_stroke, bottom, strokes_done, leaving]
