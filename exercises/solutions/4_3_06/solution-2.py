"""4.3.6, solution 2 (textbook): ADD and SUB on the rising edges of S1 and S2.

POCET (number of objects) goes up by one on each rising edge of S1 and down by one on each rising
edge of S2. The edges matter: without them ADD/SUB would run in every scan while a sensor is
covered. S1_SB and S2_SB are the edge memory bits; nothing else may write them. (INC/DEC would do
the same as ADD/SUB by one.)
"""

S1_SB = Tag("%M2.0")
S2_SB = Tag("%M2.1")


def loaded(t):
    """Network 1: -|P|- S1 (S1_SB) -> ADD POCET := POCET + 1."""
    if P(t.S1, "S1_SB"):
        t.POCET = t.POCET + 1


def arrived(t):
    """Network 2: -|P|- S2 (S2_SB) -> SUB POCET := POCET - 1."""
    if P(t.S2, "S2_SB"):
        t.POCET = t.POCET - 1


def run_belt(t):
    """Network 3: D1 := NOT S2 AND (POCET > 0)."""
    t.D1 = not t.S2 and t.POCET > 0


OB1 = [loaded, arrived, run_belt]
