"""4.3.5: an object at S1 starts the belt, the object at S2 stops it (SET and RESET)."""


def start_belt(t):
    """Network 1: an object detected at the start sets D1."""
    if t.S1:
        t.D1 = True  # S D1


def stop_belt(t):
    """Network 2: the object at the end resets D1 (later in the scan: RESET wins if both are covered)."""
    if t.S2:
        t.D1 = False  # R D1


OB1 = [start_belt, stop_belt]
