"""4.3.5 with the rungs in the other order: the object at S2 resets D1, then an object at S1 sets it.

Only one object is on the conveyor at a time, so S1 and S2 never see an object at once and the order of the
two rungs does not matter: the belt starts at S1 and stops at S2 as with the reference.
"""


def stop_belt(t):
    """Network 1: the object at the end resets D1."""
    if t.S2:
        t.D1 = False  # R D1


def start_belt(t):
    """Network 2: an object detected at the start sets D1."""
    if t.S1:
        t.D1 = True  # S D1


OB1 = [stop_belt, start_belt]
