"""Wrong (the textbook argues against it): solution 2's removal edge without "NOT M1_VPRED AND NOT M1_VZAD".

The object also leaves OS1 (a rising edge of the NC input) each time it sets off towards OS2. Without the
test that the belt stands, every departure moves 0 into the count: with two or more required moves the
count never reaches the parameter and the object shuttles without end (the textbook: "the outputs are
added so that it is a removal with the conveyor standing").
"""


def loading(t):
    """Fig. 6.30: as 6.3.1 rung 1."""
    if not t.OS1:
        if not t.OBJEKT_PRI_OS2:
            t.M1_VPRED = True  # S
        t.M1_VZAD = False  # R


def end_of_belt(t):
    """Fig. 6.31: object at OS2 -> R M1_VPRED, S M1_VZAD."""
    if not t.OS2:
        t.M1_VPRED = False  # R
        t.M1_VZAD = True  # S


def counting(t):
    """Fig. 6.32: -|N|- OS2 -> ADD 1; OBJEKT_PRI_OS2 := count reached."""
    if N(t.OS2, "POM_N_OS2"):
        t.M1_AKTUALNY_POCET = t.M1_AKTUALNY_POCET + 1  # ADD
    t.OBJEKT_PRI_OS2 = t.M1_AKTUALNY_POCET >= t.M1_ZIADANY_POCET


def removal(t):
    """-|P|- OS1 alone -> MOVE 0: also at every departure from OS1."""
    if P(t.OS1, "POM_P_OS1"):
        t.M1_AKTUALNY_POCET = 0  # MOVE


OB1 = [loading, end_of_belt, counting, removal]
