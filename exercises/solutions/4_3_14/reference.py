"""4.3.14 reference (Fig. 4.126–4.127): the conveyor of 4.3.5 plus an operating-hours meter in seconds.

Takt1s is the rising edge of the clock-memory bit Clock_1Hz (4.3.11, solution 1); while the motor
output D1 is on, each Takt1s adds one second to MOTOR.SEKUNDY (DInt, retentive). NULUJ zeroes the
meter, stores the CPU's date and time (RD_LOC_T) in MOTOR.DATUM_CAS and resets itself.
"""

TAKT_SB = Tag("%M10.0")  # edge memory of Clock_1Hz
Takt1s = Tag("%M10.1")


def start_belt(t):
    if t.S1:
        t.D1 = True


def stop_belt(t):
    if t.S2:
        t.D1 = False


def takt(t):
    """Network 1: Takt1s is TRUE for one scan every second."""
    t.Takt1s = P(t.Clock_1Hz, "TAKT_SB")


def count_seconds(t):
    """Network 2: one second more while the motor runs (ADD, DInt)."""
    if t.Takt1s and t.D1:
        t.MOTOR.SEKUNDY += 1


def reset_meter(t):
    """Network 3: NULUJ zeroes the meter, stores the date and time, and resets itself."""
    if t.MOTOR.NULUJ:
        MOVE(0, "MOTOR.SEKUNDY")
        t.MOTOR.DATUM_CAS = RD_LOC_T()
        t.MOTOR.NULUJ = False


OB1 = [start_belt, stop_belt, takt, count_seconds, reset_meter]
