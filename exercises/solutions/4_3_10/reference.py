"""4.3.10 (textbook Figs. 4.96-4.102): two conveyors, two NC light barriers each, occupancy in DB DATA.

All four sensors are wired as normally closed contacts: the input is TRUE while the beam is free and
FALSE while an object interrupts it, so "object present" is NOT D1_OS1 and so on. Four positions
(D1_POZ1_OBS at D1_OS1, D1_POZ2_OBS at D1_OS2, D2_POZ1_OBS, D2_POZ2_OBS) are set when their sensor sees
the object while the conveyor runs and the position is free, and cleared when the object reaches the
next position; the last one is cleared when the object is taken from D2_OS2 with D2 stopped. No edge
instructions: the "position free" contact in each rung makes it act once.
"""


def loading(t):
    """Fig. 4.96: an object at D1_OS1 (NC: input FALSE) occupies D1 position 1."""
    if not t.D1_OS1:
        t.DATA.D1_POZ1_OBS = True  # S


def d1_end(t):
    """Fig. 4.97: D1 running, position 2 free, object at D1_OS2 -> S D1_POZ2_OBS, R D1_POZ1_OBS."""
    if t.D1_VPRED and not t.DATA.D1_POZ2_OBS and not t.D1_OS2:
        t.DATA.D1_POZ2_OBS = True  # S
        t.DATA.D1_POZ1_OBS = False  # R


def d2_start(t):
    """Fig. 4.98: D2 running, its position 1 free, object at D2_OS1 -> S D2_POZ1_OBS, R D1_POZ2_OBS."""
    if t.D2_VPRED and not t.DATA.D2_POZ1_OBS and not t.D2_OS1:
        t.DATA.D2_POZ1_OBS = True  # S
        t.DATA.D1_POZ2_OBS = False  # R


def d2_end(t):
    """Fig. 4.99: D2 running, its position 2 free, object at D2_OS2 -> S D2_POZ2_OBS, R D2_POZ1_OBS."""
    if t.D2_VPRED and not t.DATA.D2_POZ2_OBS and not t.D2_OS2:
        t.DATA.D2_POZ2_OBS = True  # S
        t.DATA.D2_POZ1_OBS = False  # R


def removal(t):
    """Fig. 4.100: D2 stopped and no object at D2_OS2 (NC: input TRUE) -> R D2_POZ2_OBS."""
    if not t.D2_VPRED and t.D2_OS2:
        t.DATA.D2_POZ2_OBS = False  # R


def run_d1(t):
    """Fig. 4.101: D1 carries POZ1 -> POZ2, and sends POZ2 to D2 if D2 is all free."""
    t.D1_VPRED = (t.DATA.D1_POZ1_OBS and not t.DATA.D1_POZ2_OBS) or (
        t.DATA.D1_POZ2_OBS and not t.DATA.D2_POZ1_OBS and not t.DATA.D2_POZ2_OBS
    )


def run_d2(t):
    """Fig. 4.102: D2 receives from D1 (upper branch) or carries POZ1 -> POZ2 (lower branch)."""
    t.D2_VPRED = (t.DATA.D1_POZ2_OBS and not t.DATA.D2_POZ1_OBS and not t.DATA.D2_POZ2_OBS) or (
        t.DATA.D2_POZ1_OBS and not t.DATA.D2_POZ2_OBS
    )


OB1 = [loading, d1_end, d2_start, d2_end, removal, run_d1, run_d2]
