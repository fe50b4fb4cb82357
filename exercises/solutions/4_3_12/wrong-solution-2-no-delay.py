"""4.3.12, solution 2 as its text describes network 1: no 1 s delay.

The step goes 0 -> 1 in the scan in which OS sees the object, so the piston strikes at once instead
of 1 s later (criterion 1), and an object that only passes the sensor is struck too (criterion 5).
"""


def network_1(t):
    """Step 0 -> 1 as soon as an unaligned object is seen."""
    if t.OS and not t.OBJ_ZAROVNANY and t.KROK == 0:
        t.KROK = 1  # MOVE 1


def network_2(t):
    """As in solution 2."""
    t.PIEST_CHOD_VPRED = t.KROK == 1
    if t.KROK == 1 and t.PIEST_SNIMAC_VPRED:
        t.KROK = 2  # MOVE 2
    if t.KROK == 2 and t.PIEST_SNIMAC_VZAD:
        t.KROK = 0  # MOVE 0
        t.OBJ_ZAROVNANY = True  # S


def next_object(t):
    """No object any more -> R OBJ_ZAROVNANY."""
    if not t.OS:
        t.OBJ_ZAROVNANY = False  # R


OB1 = [network_1, network_2, next_object]
