"""4.3.12, solution 1 exactly as the textbook prints it: no reset of OBJ_ZAROVNANY, none of BOL_VPRED.

The first object is aligned; OBJ_ZAROVNANY then stays TRUE for ever, so the TON never runs again and
the next object is never aligned (criterion 6). BOL_VPRED stays TRUE as well.
"""

TON_Z = IEC_TIMER()


def delay(t):
    """Rung 1."""
    if t.TON_Z.TON(IN=t.OS and not t.OBJ_ZAROVNANY, PT="1s"):
        t.ZAROVNAJ = True  # S


def align(t):
    """Rung 2, branches a-c, without R BOL_VPRED."""
    back_home = P(t.PIEST_SNIMAC_VZAD, "VZAD_HRANA")
    if t.ZAROVNAJ:
        if t.PIEST_SNIMAC_VZAD and not t.BOL_VPRED:
            t.PIEST_CHOD_VPRED = True  # S
        if t.PIEST_SNIMAC_VPRED:
            t.PIEST_CHOD_VPRED = False  # R
            t.BOL_VPRED = True  # S
        if back_home:
            t.OBJ_ZAROVNANY = True  # S
            t.ZAROVNAJ = False  # R


OB1 = [delay, align]
