"""Wrong (the textbook's reason for the edge on D2_OS): arrivals registered on the sensor level.

While an object passes D2_OS with D2 running, the level-triggered rung resets D1_OBS in every scan.
The textbook: with objects seen by the sensors of both D1 and D2, D2_OS resets D1's occupancy in every
scan. When the queue advances (D2 sends its object to D3 while a new object waits at D1_OS), D1_OBS
is wiped for as long as the leaving object is in the D2_OS beam, although D1 still carries an object.
"""


def loading(t):
    """D1_OS sets D1_OBS."""
    if t.D1_OS:
        t.D1_OBS = True  # S D1_OBS


def arrival_d2(t):
    """D2_OS AND D2_VPRED -> S D2_OBS, R D1_OBS (no edge: in every scan)."""
    if t.D2_OS and t.D2_VPRED:
        t.D2_OBS = True  # S D2_OBS
        t.D1_OBS = False  # R D1_OBS


def arrival_d3(t):
    """D3_OS AND D3_VPRED -> S D3_OBS, R D2_OBS (no edge)."""
    if t.D3_OS and t.D3_VPRED:
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
