"""4.3.12 (a realistic slip): the front sensor replaced by a guessed stroke time of 0.3 s.

The piston goes back after 0.3 s whatever it reached: 24 mm of its 40 mm stroke, so the plate barely
touches the object, which is left crooked and off the fence (criterion 3), and OBJ_ZAROVNANY is set
although nothing was aligned.
"""

TON_Z = IEC_TIMER()
TON_S = IEC_TIMER()


def delay(t):
    """Rung 1."""
    if t.TON_Z.TON(IN=t.OS and not t.OBJ_ZAROVNANY, PT="1s"):
        t.ZAROVNAJ = True  # S


def align(t):
    """Out from the rear, back after 0.3 s, done at the rear."""
    back_home = P(t.PIEST_SNIMAC_VZAD, "VZAD_HRANA")
    if t.ZAROVNAJ and t.PIEST_SNIMAC_VZAD and not t.BOL_VPRED:
        t.PIEST_CHOD_VPRED = True  # S
    if t.TON_S.TON(IN=t.PIEST_CHOD_VPRED, PT="300ms"):
        t.PIEST_CHOD_VPRED = False  # R
        t.BOL_VPRED = True  # S
    if t.ZAROVNAJ and t.BOL_VPRED and back_home:
        t.OBJ_ZAROVNANY = True  # S
        t.ZAROVNAJ = False  # R
        t.BOL_VPRED = False  # R


def next_object(t):
    """Rung 3."""
    if not t.OS:
        t.OBJ_ZAROVNANY = False  # R


OB1 = [delay, align, next_object]
