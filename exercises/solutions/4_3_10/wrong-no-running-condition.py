"""Wrong (the textbook's remark on Fig. 4.97): position 2 of D1 registered without the D1_VPRED contact.

The textbook: an object put directly in front of D1_OS2 on an idle model is not registered, because
the conveyor is not running. Without the D1_VPRED contact it is: D1_POZ2_OBS is set and D1 and D2
start and carry an object that nobody loaded at D1_OS1.
"""


def loading(t):
    """Fig. 4.96: an object at D1_OS1 (NC: input FALSE) occupies D1 position 1."""
    if not t.D1_OS1:
        t.DATA.D1_POZ1_OBS = True  # S


def d1_end(t):
    """Position 2 free, object at D1_OS2 -> S D1_POZ2_OBS, R D1_POZ1_OBS (no D1_VPRED contact)."""
    if not t.DATA.D1_POZ2_OBS and not t.D1_OS2:
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
