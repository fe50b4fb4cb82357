"""4.3.12, solution 1 (textbook Figs. 4.108-4.112) with the resets the text does not show.

Rung 1: TON_Z times while the object is seen and not yet aligned; after 1 s its Q sets ZAROVNAJ.
Rung 2, while ZAROVNAJ: (a) at the rear and not yet forward -> S PIEST_CHOD_VPRED; (b) at the front
-> R PIEST_CHOD_VPRED, S BOL_VPRED ("was forward": blocks a second forward stroke); (c) the rising
edge of the rear sensor (back home) -> S OBJ_ZAROVNANY, R ZAROVNAJ, and R BOL_VPRED [R: where it is
reset is not stated]. The P contact compares PIEST_SNIMAC_VZAD with its edge memory in every scan
(the power flow only gates its result), so it is evaluated before the branch test.
Rung 3 [R, not in the text]: the object gone (OS FALSE) -> R OBJ_ZAROVNANY, so the next one is aligned.
"""

TON_Z = IEC_TIMER()


def delay(t):
    """Rung 1: TON_Z(IN := OS AND NOT OBJ_ZAROVNANY, PT := 1 s); Q -> S ZAROVNAJ."""
    if t.TON_Z.TON(IN=t.OS and not t.OBJ_ZAROVNANY, PT="1s"):
        t.ZAROVNAJ = True  # S


def align(t):
    """Rung 2: the three branches under ZAROVNAJ."""
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
    """Rung 3: no object any more -> R OBJ_ZAROVNANY."""
    if not t.OS:
        t.OBJ_ZAROVNANY = False  # R


OB1 = [delay, align, next_object]
