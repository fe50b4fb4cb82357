"""A typical slip (not from the textbook): NULUJ zeroes only SEKUNDY, as in 4.3.14.

The meter then keeps its minutes and hours through a reset: an operator reads the running time since
the last reset wrong by whole minutes and hours (criterion 3 of 4.3.15: NULUJ resets all three).
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


def count_seconds(t):
    if t.Takt1s and t.D1:
        t.MOTOR.SEKUNDY += 1


def carry_minutes(t):
    if t.MOTOR.SEKUNDY >= 60:
        t.MOTOR.MINUTY += 1
        MOVE(0, "MOTOR.SEKUNDY")


def carry_hours(t):
    if t.MOTOR.MINUTY >= 60:
        t.MOTOR.HODINY += 1
        MOVE(0, "MOTOR.MINUTY")


def reset_meter(t):
    if t.MOTOR.NULUJ:
        MOVE(0, "MOTOR.SEKUNDY")
        t.MOTOR.DATUM_CAS = RD_LOC_T()
        t.MOTOR.NULUJ = False


OB1 = [start_belt, stop_belt, takt, count_seconds, carry_minutes, carry_hours, reset_meter]
