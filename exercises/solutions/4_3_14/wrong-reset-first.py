"""A network-order slip (not from the textbook): the reset network comes before the counting network.

When the scan that reads NULUJ is also the scan of the 1 s pulse, the meter is zeroed and then counts
that second in the same scan: at the end of the reset scan SEKUNDY is 1, not 0 (criterion 2 of 4.3.14
asks for 0 "in the same scan"). The textbook counts first and resets last.
"""

TAKT_SB = Tag("%M10.0")
Takt1s = Tag("%M10.1")


def start_belt(t):
    if t.S1:
        t.D1 = True


def stop_belt(t):
    if t.S2:
        t.D1 = False


def takt(t):
    t.Takt1s = P(t.Clock_1Hz, "TAKT_SB")


def reset_meter(t):
    if t.MOTOR.NULUJ:
        MOVE(0, "MOTOR.SEKUNDY")
        t.MOTOR.DATUM_CAS = RD_LOC_T()
        t.MOTOR.NULUJ = False


def count_seconds(t):
    if t.Takt1s and t.D1:
        t.MOTOR.SEKUNDY += 1


OB1 = [start_belt, stop_belt, takt, reset_meter, count_seconds]
