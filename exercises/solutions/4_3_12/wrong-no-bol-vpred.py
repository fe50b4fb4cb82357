"""4.3.12, solution 1 without BOL_VPRED ("it blocks a repeated forward motion", the textbook says).

Back at the rear, branch (a) sets PIEST_CHOD_VPRED again in the same scan in which branch (c) ends
the cycle and resets ZAROVNAJ: the piston goes out a second time, and with ZAROVNAJ FALSE branch (b)
never takes it back. Two strokes, and the piston stays out (criteria 2 and 4).
"""

TON_Z = IEC_TIMER()


def delay(t):
    """Rung 1."""
    if t.TON_Z.TON(IN=t.OS and not t.OBJ_ZAROVNANY, PT="1s"):
        t.ZAROVNAJ = True  # S


def align(t):
    """Rung 2 without the BOL_VPRED contact and coils."""
    back_home = P(t.PIEST_SNIMAC_VZAD, "VZAD_HRANA")
    if t.ZAROVNAJ:
        if t.PIEST_SNIMAC_VZAD:
            t.PIEST_CHOD_VPRED = True  # S
        if t.PIEST_SNIMAC_VPRED:
            t.PIEST_CHOD_VPRED = False  # R
        if back_home:
            t.OBJ_ZAROVNANY = True  # S
            t.ZAROVNAJ = False  # R


def next_object(t):
    """Rung 3."""
    if not t.OS:
        t.OBJ_ZAROVNANY = False  # R


OB1 = [delay, align, next_object]
