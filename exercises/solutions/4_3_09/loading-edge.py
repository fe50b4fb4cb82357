"""4.3.9, alternative: the reference with loading on the rising edge of D1_OS (edge bit SB1).

The prose says "activation of D1_OS sets D1_OBS"; the tag table's SB1 suggests the figure may use an
edge. Both work: D1_OBS is only reset when the object reaches D2_OS.

The rest as the reference (textbook Figs. 4.88-4.93):

An object moves on only if its conveyor is occupied and the next one is free. D2_OS and D3_OS register
an arrival on their rising edge, and only while the receiving conveyor runs (a hand shading a sensor
of a stopped line registers nothing; the edge keeps D2_OS from resetting D1_OBS in every scan while it
sees an object). The object at D3 is taken away by hand: the falling edge of D3_OS while D3 stands
clears D3_OBS.

Text issue: the tag table declares SB1-SB3, but the program needs three edge bits for D2_OS rising,
D3_OS rising and D3_OS falling; the P and the N on D3_OS must not share one. SB1 is left for an edge
on D1_OS (not used: loading is level-triggered, as the prose says), and the falling edge uses SB4
(%M2.3, added).
"""


def loading(t):
    """Fig. 4.88 top: -|P|- D1_OS (SB1) sets D1_OBS."""
    if P(t.D1_OS, "SB1"):
        t.D1_OBS = True  # S D1_OBS


def arrival_d2(t):
    """Fig. 4.88 bottom: -|P|- D2_OS (SB2) AND D2_VPRED -> S D2_OBS, R D1_OBS."""
    if P(t.D2_OS, "SB2") and t.D2_VPRED:
        t.D2_OBS = True  # S D2_OBS
        t.D1_OBS = False  # R D1_OBS


def arrival_d3(t):
    """Fig. 4.89: -|P|- D3_OS (SB3) AND D3_VPRED -> S D3_OBS, R D2_OBS."""
    if P(t.D3_OS, "SB3") and t.D3_VPRED:
        t.D3_OBS = True  # S D3_OBS
        t.D2_OBS = False  # R D2_OBS


def removal_d3(t):
    """Fig. 4.90: -|N|- D3_OS (SB4) AND NOT D3_VPRED -> R D3_OBS (the object was taken away)."""
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
