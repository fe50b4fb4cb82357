"""4.3.22, the textbook's program (Fig. 4.186) in OB30: -|P|- TL (edge memory SB1) -> ADD D.CISLO + 1.

The edge is found by comparing TL as sampled by this call with the value SB1 kept from the last
call. A press between two calls is lost; an input already TRUE at STOP->RUN gives an edge at the
first call, because SB1 (non-retentive %M) was cleared.
"""


def count_presses(t):
    if P(t.TL, "SB1"):
        t.D.CISLO = t.D.CISLO + 1  # ADD


OB30 = CyclicInterrupt(count_presses, period="1s")
