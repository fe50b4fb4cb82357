"""4.3.17 (a slip): the colour intervals drawn as thresholds, with no outer bounds.

"Below 9000 is colour 1, 9001-17000 colour 2, above 17000 colour 3": the three colours and the light
allowances are the textbook's, and every object of the three colours is sorted. An object of none of them
is not: a black one (darker than colour 3) reads as colour 3 and a polished one (brighter than colour 1) as
colour 1, and each is pushed into that colour's bin.
"""

TON_P1 = IEC_TIMER()
TON_P2 = IEC_TIMER()
TON_P3 = IEC_TIMER()


def loading(t):
    """Rung 1 (4.150): an object at OS1 occupies position 1."""
    if not t.OS1_Vstup:
        t.DATA.POZ1_OBS_Nakladanie = True  # S


def detection(t):
    """Rung 2 (4.151): at OS2, position 2 taken, position 1 freed, the colour classified once."""
    if t.D1_VPRED and not t.DATA.POZ2_OBS_Detekcia and not t.OS2_Detekcia:
        t.DATA.POZ2_OBS_Detekcia = True  # S
        t.DATA.POZ1_OBS_Nakladanie = False  # R
        if t.FARBA <= 9000:
            t.DATA.POZ2_DETEKCIA = 1  # MOVE
        if IN_RANGE(9001, t.FARBA, 17000):
            t.DATA.POZ2_DETEKCIA = 2  # MOVE
        if t.FARBA > 17000:
            t.DATA.POZ2_DETEKCIA = 3  # MOVE


def colour_1(t):
    """Rung 3 (4.152): at OS3, position 3 taken, the type copied from position 2 and cleared there."""
    if t.D1_VPRED and not t.DATA.POZ3_OBS_Farba1 and not t.OS3_Farba1:
        t.DATA.POZ3_OBS_Farba1 = True  # S
        t.DATA.POZ2_OBS_Detekcia = False  # R
        t.DATA.POZ3_FARBA1 = t.DATA.POZ2_DETEKCIA  # MOVE
        t.DATA.POZ2_DETEKCIA = 0  # MOVE


def colour_2(t):
    """Rung 4 (4.153): position 3 -> 4 at OS4."""
    if t.D1_VPRED and not t.DATA.POZ4_OBS_Farba2 and not t.OS4_Farba2:
        t.DATA.POZ4_OBS_Farba2 = True  # S
        t.DATA.POZ3_OBS_Farba1 = False  # R
        t.DATA.POZ4_FARBA2 = t.DATA.POZ3_FARBA1  # MOVE
        t.DATA.POZ3_FARBA1 = 0  # MOVE


def colour_3(t):
    """Rung 5 (4.154): position 4 -> 5 at OS5."""
    if t.D1_VPRED and not t.DATA.POZ5_OBS_Farba3 and not t.OS5_Farba3:
        t.DATA.POZ5_OBS_Farba3 = True  # S
        t.DATA.POZ4_OBS_Farba2 = False  # R
        t.DATA.POZ5_FARBA3 = t.DATA.POZ4_FARBA2  # MOVE
        t.DATA.POZ4_FARBA2 = 0  # MOVE


def conveyor(t):
    """Rung 6 (4.155): the belt runs while any position is occupied."""
    d = t.DATA
    t.D1_VPRED = (
        d.POZ1_OBS_Nakladanie or d.POZ2_OBS_Detekcia or d.POZ3_OBS_Farba1 or d.POZ4_OBS_Farba2 or d.POZ5_OBS_Farba3
    )


def compressor(t):
    """Rung 7 (4.156): the compressor runs while any piston is out."""
    t.Kompresor = t.Piest1_Farba1 or t.Piest2_Farba2 or t.Piest3_Farba3


def piston_1(t):
    """Rung 8 (4.157): colour 1 just past OS3 -> piston 1 for 1 s; then position 3 is free."""
    if t.DATA.POZ3_OBS_Farba1 and t.OS3_Farba1 and t.DATA.POZ3_FARBA1 == 1:
        t.Piest1_Farba1 = True  # S
    if t.TON_P1.TON(IN=t.Piest1_Farba1, PT="1s"):
        t.Piest1_Farba1 = False  # R
        t.DATA.POZ3_OBS_Farba1 = False  # R
        t.DATA.POZ3_FARBA1 = 0  # MOVE


def piston_2(t):
    """Rung 9 (4.158): the same for piston 2 at OS4."""
    if t.DATA.POZ4_OBS_Farba2 and t.OS4_Farba2 and t.DATA.POZ4_FARBA2 == 2:
        t.Piest2_Farba2 = True  # S
    if t.TON_P2.TON(IN=t.Piest2_Farba2, PT="1s"):
        t.Piest2_Farba2 = False  # R
        t.DATA.POZ4_OBS_Farba2 = False  # R
        t.DATA.POZ4_FARBA2 = 0  # MOVE


def piston_3(t):
    """Rung 10 (4.159): the same for piston 3 at OS5."""
    if t.DATA.POZ5_OBS_Farba3 and t.OS5_Farba3 and t.DATA.POZ5_FARBA3 == 3:
        t.Piest3_Farba3 = True  # S
    if t.TON_P3.TON(IN=t.Piest3_Farba3, PT="1s"):
        t.Piest3_Farba3 = False  # R
        t.DATA.POZ5_OBS_Farba3 = False  # R
        t.DATA.POZ5_FARBA3 = 0  # MOVE


OB1 = [loading, detection, colour_1, colour_2, colour_3, conveyor, compressor, piston_1, piston_2, piston_3]
