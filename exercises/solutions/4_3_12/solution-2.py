"""4.3.12, solution 2 (textbook Figs. 4.114-4.120): a step variable KROK 0 -> 1 -> 2 -> 0.

Network 1: in step 0, an object seen and not yet aligned for 1 s (TON_Z; the text does not mention
the delay [R], the task requires it) -> KROK := 1.
Network 2: PIEST_CHOD_VPRED := (KROK == 1); step 1 at the front -> KROK := 2 (the piston returns);
step 2 at the rear -> KROK := 0 and S OBJ_ZAROVNANY. Plus the reset of OBJ_ZAROVNANY when the object
is gone [R], as in solution 1.
"""

TON_Z = IEC_TIMER()


def network_1(t):
    """Step 0 -> 1 one second after an unaligned object is seen."""
    if t.TON_Z.TON(IN=t.OS and not t.OBJ_ZAROVNANY and t.KROK == 0, PT="1s"):
        t.KROK = 1  # MOVE 1


def network_2(t):
    """The piston follows step 1; the end sensors advance the steps."""
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
