"""4.3.15 reference (Fig. 4.130–4.131): the meter in seconds, minutes and hours.

SEKUNDY and MINUTY (USInt) carry into the next unit at 60 in the same scan; HODINY is UInt.
NULUJ zeroes all three with one MOVE with three outputs and stores the date and time as in 4.3.14.
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
    """Network 1: one second more while the motor runs."""
    if t.Takt1s and t.D1:
        t.MOTOR.SEKUNDY += 1


def carry_minutes(t):
    """Network 2: 60 seconds make a minute."""
    if t.MOTOR.SEKUNDY >= 60:
        t.MOTOR.MINUTY += 1
        MOVE(0, "MOTOR.SEKUNDY")


def carry_hours(t):
    """Network 3: 60 minutes make an hour."""
    if t.MOTOR.MINUTY >= 60:
        t.MOTOR.HODINY += 1
        MOVE(0, "MOTOR.MINUTY")


def reset_meter(t):
    """Network 4: NULUJ zeroes the meter (MOVE with three outputs) and stores the date and time."""
    if t.MOTOR.NULUJ:
        MOVE(0, "MOTOR.SEKUNDY", "MOTOR.MINUTY", "MOTOR.HODINY")
        t.MOTOR.DATUM_CAS = RD_LOC_T()
        t.MOTOR.NULUJ = False


OB1 = [start_belt, stop_belt, takt, count_seconds, carry_minutes, carry_hours, reset_meter]
