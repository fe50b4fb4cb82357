"""4.3.12 (not from the textbook): the TON input without NOT OBJ_ZAROVNANY.

While the object stays, TON_Z.Q stays TRUE and sets ZAROVNAJ again in the scan after each cycle
ends: the piston strikes the aligned object again and again (criterion 4).
"""

TON_Z = IEC_TIMER()


def delay(t):
    """Rung 1 with IN := OS only."""
    if t.TON_Z.TON(IN=t.OS, PT="1s"):
        t.ZAROVNAJ = True  # S


def align(t):
    """Rung 2 as in the reference."""
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
            t.BOL_VPRED = False  # R


def next_object(t):
    """Rung 3."""
    if not t.OS:
        t.OBJ_ZAROVNANY = False  # R


OB1 = [delay, align, next_object]
