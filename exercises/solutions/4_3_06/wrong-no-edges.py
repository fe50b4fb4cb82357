"""Wrong (the textbook's warning in solution 2): ADD and SUB without edge instructions.

The textbook explains why solution 2 needs -|P|-: without it, ADD runs in every scan while S1 sees
the object and SUB in every scan while S2 does. One object loaded adds a few hundred (one per 1 ms
scan for as long as it covers S1), the object waiting at S2 subtracts about a thousand, so POCET has
nothing to do with the number of objects and the belt stops for good.
"""


def loaded(t):
    """Network 1: S1 -> ADD POCET := POCET + 1 (in every scan S1 is TRUE)."""
    if t.S1:
        t.POCET = t.POCET + 1


def arrived(t):
    """Network 2: S2 -> SUB POCET := POCET - 1 (in every scan S2 is TRUE)."""
    if t.S2:
        t.POCET = t.POCET - 1


def run_belt(t):
    """Network 3: D1 := NOT S2 AND (POCET > 0)."""
    t.D1 = not t.S2 and t.POCET > 0


OB1 = [loaded, arrived, run_belt]
