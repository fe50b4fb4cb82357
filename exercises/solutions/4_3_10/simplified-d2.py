"""4.3.10, the textbook's simplified drive of D2 (Fig. 4.103; exact form not visible [R]).

D2_VPRED := (D1_POZ2_OBS OR D2_POZ1_OBS) AND NOT D2_POZ2_OBS. It differs from Fig. 4.102 only when D1
holds an object at POZ2 while D2 carries one between POZ1 and POZ2: D2 runs in both cases, and D1 waits
because its rung still requires D2 to be all free. The rest as the reference.
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
    """Fig. 4.103: D2_VPRED := (D1_POZ2_OBS OR D2_POZ1_OBS) AND NOT D2_POZ2_OBS."""
    t.D2_VPRED = (t.DATA.D1_POZ2_OBS or t.DATA.D2_POZ1_OBS) and not t.DATA.D2_POZ2_OBS


OB1 = [loading, d1_end, d2_start, d2_end, removal, run_d1, run_d2]
