"""4.3.6, solution 1 (textbook): an up/down counter CTUD counts the objects on the belt.

CU is S1 (+1 on each rising edge of S1: an object loaded), CD is S2 (-1 on each rising edge of S2:
an object arrived at the end). The belt runs while the end is free and at least one object is on it.
The box's CV output is wired to POCET (number of objects), so the count can be watched like the
POCET of solution 2; the textbook's rung compares CV itself.
"""

IEC_Counter_0_DB = IEC_COUNTER()


def count_objects(t):
    """Network 1: CTUD, CU := S1, CD := S2, CV => POCET."""
    t.IEC_Counter_0_DB.CTUD(CU=t.S1, CD=t.S2, R=False, LD=False, PV=0)
    t.POCET = t.IEC_Counter_0_DB.CV


def run_belt(t):
    """Network 2: D1 := NOT S2 AND (CV > 0)."""
    t.D1 = not t.S2 and t.IEC_Counter_0_DB.CV > 0


OB1 = [count_objects, run_belt]
