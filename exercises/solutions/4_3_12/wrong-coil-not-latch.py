"""4.3.12 (a realistic slip): the piston output as a plain coil, ZAROVNAJ AND NOT PIEST_SNIMAC_VPRED.

At the front the valve closes, but as soon as the spring has moved the plate off the front sensor the
coil opens the valve again: the plate hammers at the front and never gets back to the rear, so the
cycle never ends (criterion 2: one full stroke, back at the rear).
"""

TON_Z = IEC_TIMER()


def delay(t):
    """Rung 1."""
    if t.TON_Z.TON(IN=t.OS and not t.OBJ_ZAROVNANY, PT="1s"):
        t.ZAROVNAJ = True  # S


def align(t):
    """The valve follows ZAROVNAJ until the front; back home ends the cycle."""
    back_home = P(t.PIEST_SNIMAC_VZAD, "VZAD_HRANA")
    t.PIEST_CHOD_VPRED = t.ZAROVNAJ and not t.PIEST_SNIMAC_VPRED
    if t.ZAROVNAJ and back_home:
        t.OBJ_ZAROVNANY = True  # S
        t.ZAROVNAJ = False  # R


def next_object(t):
    """Rung 3."""
    if not t.OS:
        t.OBJ_ZAROVNANY = False  # R


OB1 = [delay, align, next_object]
