"""Wrong (a typical slip, not from the textbook): the NC sensors read as if they were NO.

All four barriers are wired as normally closed contacts: TRUE means the beam is free. A program that
takes TRUE for "object present" sees an object at every free sensor: position 1 of D1 is occupied as
soon as the CPU starts, D1 runs with nothing on it, and real objects are seen only when they leave.
"""


def loading(t):
    """D1_OS1 TRUE taken for "object present" (it means "beam free")."""
    if t.D1_OS1:
        t.DATA.D1_POZ1_OBS = True  # S


def d1_end(t):
    """Fig. 4.97: D1 running, position 2 free, object at D1_OS2 -> S D1_POZ2_OBS, R D1_POZ1_OBS."""
    if t.D1_VPRED and not t.DATA.D1_POZ2_OBS and t.D1_OS2:
        t.DATA.D1_POZ2_OBS = True  # S
        t.DATA.D1_POZ1_OBS = False  # R


def d2_start(t):
    """Fig. 4.98: D2 running, its position 1 free, object at D2_OS1 -> S D2_POZ1_OBS, R D1_POZ2_OBS."""
    if t.D2_VPRED and not t.DATA.D2_POZ1_OBS and t.D2_OS1:
        t.DATA.D2_POZ1_OBS = True  # S
        t.DATA.D1_POZ2_OBS = False  # R


def d2_end(t):
    """Fig. 4.99: D2 running, its position 2 free, object at D2_OS2 -> S D2_POZ2_OBS, R D2_POZ1_OBS."""
    if t.D2_VPRED and not t.DATA.D2_POZ2_OBS and t.D2_OS2:
        t.DATA.D2_POZ2_OBS = True  # S
        t.DATA.D2_POZ1_OBS = False  # R


def removal(t):
    """D2 stopped and D2_OS2 FALSE taken for "no object" -> R D2_POZ2_OBS."""
    if not t.D2_VPRED and not t.D2_OS2:
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
