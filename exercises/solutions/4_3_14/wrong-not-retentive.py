"""A typical slip (not from the textbook): the seconds are counted in the program's own tag, which
is not retentive, and copied into the DB. At STOP->RUN the own tag starts again from 0 and the copy
wipes the retentive MOTOR.SEKUNDY: the hours of running are lost (textbook §3.6.2, 4.3.14)."""

TAKT_SB = Tag("%M10.0")
SECONDS = DInt(0)


def start_belt(t):
    if t.S1:
        t.D1 = True


def stop_belt(t):
    if t.S2:
        t.D1 = False


def count_seconds(t):
    if P(t.Clock_1Hz, "TAKT_SB") and t.D1:
        t.SECONDS += 1
    if t.MOTOR.NULUJ:
        t.SECONDS = 0
        t.MOTOR.DATUM_CAS = RD_LOC_T()
        t.MOTOR.NULUJ = False
    t.MOTOR.SEKUNDY = t.SECONDS


OB1 = [start_belt, stop_belt, count_seconds]
