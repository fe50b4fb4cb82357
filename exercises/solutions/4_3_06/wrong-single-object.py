"""Wrong for 4.3.6: the one-object solution of 4.3.5 (S1 -> SET D1, S2 -> RESET D1), unchanged.

The textbook's point for 4.3.6: sensors and the output alone are not enough. The first object at S2
stops the belt while a second one is still in the middle; after the first is removed nothing
remembers that objects are left between S1 and S2, so the belt stays off and they never arrive
(until a new object happens to pass S1).
"""


def start_belt(t):
    """Network 1: an object detected at the start sets D1."""
    if t.S1:
        t.D1 = True  # S D1


def stop_belt(t):
    """Network 2: the object at the end resets D1."""
    if t.S2:
        t.D1 = False  # R D1


OB1 = [start_belt, stop_belt]
