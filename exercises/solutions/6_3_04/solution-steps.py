"""6.3.4 written as a step sequencer (not from the textbook): one step variable KROK instead of SET/RESET rungs.

0 idle: an object at OS1 starts the belt forward (step 1). 1 forward: at OS2 the belt stops and the move is
counted (step 2). 2 down: the press goes down until KS2 (step 3). 3 up: the press goes up until KS1; there the
object is sent back in the same scan (step 4). 4 back: at OS1 the belt stops; after M1_ZIADANY_POCET moves the
object waits for its removal (step 5), else it goes forward again. 5 waiting: once the OS1 beam is free again the
count is cleared (step 0). A correct program written differently from the textbook's: taken from under the press,
the object is never seen back at OS1, so this program runs the belt back towards OS1 (the task does not say what
it should do then).
"""

KROK = Int(0)


def sequence(t):
    """The steps; each transition writes the outputs of the new step in the same scan."""
    if t.KROK == 0 and not t.OS1:
        t.KROK = 1
        t.M1_VPRED = True
    elif t.KROK == 1 and not t.OS2:
        t.M1_VPRED = False
        t.M1_AKTUALNY_POCET = t.M1_AKTUALNY_POCET + 1
        t.KROK = 2
    if t.KROK == 2:
        t.M2_DOLE = not t.KS2
        if t.KS2:
            t.KROK = 3
    if t.KROK == 3:
        t.M2_HORE = not t.KS1
        if t.KS1:
            t.KROK = 4
            t.M1_VZAD = True
    elif t.KROK == 4 and not t.OS1:
        t.M1_VZAD = False
        if t.M1_AKTUALNY_POCET >= t.M1_ZIADANY_POCET:
            t.KROK = 5
        else:
            t.KROK = 1
            t.M1_VPRED = True
    elif t.KROK == 5 and t.OS1:
        t.M1_AKTUALNY_POCET = 0
        t.KROK = 0


OB1 = [sequence]
