"""A scan-order slip (not from the textbook): the carry networks come before the counting network.

The second that makes SEKUNDY 60 is added after the carry has already been checked in that scan, so
for one scan the meter shows 60 s (and 60 min): what an operator panel reads at the end of the scan
is wrong, although the total still adds up. The textbook's order counts first, then carries, so that
"the carry happens in the same scan" (criterion 1 of 4.3.15)."""

TAKT_SB = Tag("%M10.0")


def start_belt(t):
    if t.S1:
        t.D1 = True


def stop_belt(t):
    if t.S2:
        t.D1 = False


def carry_minutes(t):
    if t.MOTOR.SEKUNDY >= 60:
        t.MOTOR.MINUTY += 1
        MOVE(0, "MOTOR.SEKUNDY")


def carry_hours(t):
    if t.MOTOR.MINUTY >= 60:
        t.MOTOR.HODINY += 1
        MOVE(0, "MOTOR.MINUTY")


def count_seconds(t):
    if P(t.Clock_1Hz, "TAKT_SB") and t.D1:
        t.MOTOR.SEKUNDY += 1


def reset_meter(t):
    if t.MOTOR.NULUJ:
        MOVE(0, "MOTOR.SEKUNDY", "MOTOR.MINUTY", "MOTOR.HODINY")
        t.MOTOR.DATUM_CAS = RD_LOC_T()
        t.MOTOR.NULUJ = False


OB1 = [start_belt, stop_belt, carry_minutes, carry_hours, count_seconds, reset_meter]
