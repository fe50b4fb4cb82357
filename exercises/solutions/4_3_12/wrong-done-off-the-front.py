"""4.3.12 (a slip): solution 2 with step 2 ended by "no longer at the front" instead of "at the rear".

The plate has only just left the front sensor when OBJ_ZAROVNANY says "aligned": a robot that takes the
object then meets the plate on its way back (the task aligns the object so that the robot does not
collide). With the rear sensor dead it still reports the object aligned, which the program cannot know.
"""

TON_Z = IEC_TIMER()


def network_1(t):
    """Step 0 -> 1 one second after an unaligned object is seen."""
    if t.TON_Z.TON(IN=t.OS and not t.OBJ_ZAROVNANY and t.KROK == 0, PT="1s"):
        t.KROK = 1  # MOVE 1


def network_2(t):
    """The piston follows step 1; step 2 ends when the front sensor is released."""
    t.PIEST_CHOD_VPRED = t.KROK == 1
    if t.KROK == 1 and t.PIEST_SNIMAC_VPRED:
        t.KROK = 2  # MOVE 2
    if t.KROK == 2 and not t.PIEST_SNIMAC_VPRED:
        t.KROK = 0  # MOVE 0
        t.OBJ_ZAROVNANY = True  # S


def next_object(t):
    """No object any more -> R OBJ_ZAROVNANY."""
    if not t.OS:
        t.OBJ_ZAROVNANY = False  # R


OB1 = [network_1, network_2, next_object]
