"""Wrong (the textbook's reason for the D2_VPRED / D3_VPRED contacts): arrivals registered without them.

The textbook: the running condition in the arrival rungs keeps a hand that shades a sensor of a stopped,
empty line from occupying a position. Without it, a hand in front of D2_OS sets D2_OBS; D2 (and D3)
start for an object that is not there.
"""


def loading(t):
    """D1_OS sets D1_OBS."""
    if t.D1_OS:
        t.D1_OBS = True  # S D1_OBS


def arrival_d2(t):
    """-|P|- D2_OS (SB2) -> S D2_OBS, R D1_OBS (no D2_VPRED contact)."""
    if P(t.D2_OS, "SB2"):
        t.D2_OBS = True  # S D2_OBS
        t.D1_OBS = False  # R D1_OBS


def arrival_d3(t):
    """-|P|- D3_OS (SB3) -> S D3_OBS, R D2_OBS (no D3_VPRED contact)."""
    if P(t.D3_OS, "SB3"):
        t.D3_OBS = True  # S D3_OBS
        t.D2_OBS = False  # R D2_OBS


def removal_d3(t):
    """-|N|- D3_OS (SB4) AND NOT D3_VPRED -> R D3_OBS."""
    if N(t.D3_OS, "SB4") and not t.D3_VPRED:
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
