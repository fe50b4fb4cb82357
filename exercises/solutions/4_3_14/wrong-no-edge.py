"""A typical slip (not from the textbook): Clock_1Hz as a plain contact instead of its rising edge.

The ADD then runs in every scan of the half second in which Clock_1Hz is TRUE (5 times a second at a
100 ms cycle), exactly what the textbook warns about for ADD without an edge (§3.4.1, 4.2.1).
"""


def start_belt(t):
    if t.S1:
        t.D1 = True


def stop_belt(t):
    if t.S2:
        t.D1 = False


def count_seconds(t):
    if t.Clock_1Hz and t.D1:
        t.MOTOR.SEKUNDY += 1


def reset_meter(t):
    if t.MOTOR.NULUJ:
        MOVE(0, "MOTOR.SEKUNDY")
        t.MOTOR.DATUM_CAS = RD_LOC_T()
        t.MOTOR.NULUJ = False


OB1 = [start_belt, stop_belt, count_seconds, reset_meter]
