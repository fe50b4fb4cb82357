"""4.3.11, solution 1: the rising edge of the clock-memory bit Clock_1Hz.

Clock_1Hz (%M0.5 with clock memory at MB0) changes its state every 0.5 s; its rising edge is TRUE
for one scan every 1.000 s exactly. The edge instruction needs a memory bit of its own (the textbook
does not name it; %M10.3 is proposed).
"""

AUX = Tag("%M10.3")  # edge memory bit of P


def OB1(t):
    t.Takt1s = P(t.Clock_1Hz, "AUX")
