"""Wrong (from the textbook's tag table, not one of its solutions): the P and the N on D3_OS share SB3.

The tag table declares only SB1-SB3 for the edges. A student who puts the rising and the falling edge
of D3_OS on the same bit SB3 gets an N that never fires: the P instruction has already written the
current value of D3_OS into SB3 when the N compares with it. D3_OBS is never cleared after the
object is taken away, and the line stands still for good after the first object.
"""


def loading(t):
    """D1_OS sets D1_OBS."""
    if t.D1_OS:
        t.D1_OBS = True  # S D1_OBS


def arrival_d2(t):
    """-|P|- D2_OS (SB2) AND D2_VPRED -> S D2_OBS, R D1_OBS."""
    if P(t.D2_OS, "SB2") and t.D2_VPRED:
        t.D2_OBS = True  # S D2_OBS
        t.D1_OBS = False  # R D1_OBS


def arrival_d3(t):
    """-|P|- D3_OS (SB3) AND D3_VPRED -> S D3_OBS, R D2_OBS."""
    if P(t.D3_OS, "SB3") and t.D3_VPRED:
        t.D3_OBS = True  # S D3_OBS
        t.D2_OBS = False  # R D2_OBS


def removal_d3(t):
    """-|N|- D3_OS (SB3, the same bit!) AND NOT D3_VPRED -> R D3_OBS."""
    if N(t.D3_OS, "SB3") and not t.D3_VPRED:
        t.D3_OBS = False  # R D3_OBS


def run_d1(t):
    """Fig. 4.91: D1 only sends: D1_VPRED := D1_OBS AND NOT D2_OBS."""
    t.D1_VPRED = t.D1_OBS and not t.D2_OBS


def run_d2(t):
    """Fig. 4.92: D2 receives (upper branch) or sends (lower branch)."""
    t.D2_VPRED = (t.D1_OBS and not t.D2_OBS) or (t.D2_OBS and not t.D3_OBS)


def run_d3(t):
    """Fig. 4.93: D3 only receives: D3_VPRED := D2_OBS AND NOT D3_OBS."""
    t.D3_VPRED = t.D2_OBS and not t.D3_OBS


OB1 = [loading, arrival_d2, arrival_d3, removal_d3, run_d1, run_d2, run_d3]
