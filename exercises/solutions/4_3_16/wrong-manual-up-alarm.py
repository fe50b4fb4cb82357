"""4.3.16, wrong: the textbook's N11 as printed, the up alarm not restricted to AUTO.

Manual travel is always slow: a full manual ascent takes about 41 s and raises ALARM_NEDOSIEL_HORE after 32 s
although nothing is wrong.
"""

TON_V = IEC_TIMER()
TON_H = IEC_TIMER()
TON_D = IEC_TIMER()


def slow_down_alarm(t):
    """N13, version 1: the skip arrived at the top moving up without POZ2 -> the slow-down sensor failed."""
    if t.START_HORE and t.SNIMAC_HORNY and not t.DB_SKIP.POZ2:
        t.DB_SKIP.ALARM_CHYBA_SPOMAL_SN = True  # S


def directions(t):
    """N1, N2: the direction outputs from the automatic or the manual commands, never into an end sensor."""
    s = t.DB_SKIP
    manual_up = s.MAN_HORE and not s.MAN_DOLE
    manual_down = s.MAN_DOLE and not s.MAN_HORE
    t.START_HORE = ((s.AUTO and s.AUTO_HORE) or (not s.AUTO and manual_up)) and not t.SNIMAC_HORNY
    t.START_DOLE = (
        ((s.AUTO and s.AUTO_DOLE) or (not s.AUTO and manual_down)) and not t.SNIMAC_DOLNY and not t.START_HORE
    )


def positions(t):
    """N3-N5: POZ1/POZ2 set on leaving a sensor in the direction of travel, reset at every sensor."""
    left_bottom = N(t.SNIMAC_DOLNY, "HRANA_DOLNY")
    left_slow_1 = N(t.SNIMAC_SPOMAL, "HRANA_SPOMAL_1")
    left_slow_2 = N(t.SNIMAC_SPOMAL, "HRANA_SPOMAL_2")
    left_top = N(t.SNIMAC_HORNY, "HRANA_HORNY")
    if (t.START_HORE and left_bottom) or (t.START_DOLE and left_slow_1):
        t.DB_SKIP.POZ1 = True  # S
    if (t.START_HORE and left_slow_2) or (t.START_DOLE and left_top):
        t.DB_SKIP.POZ2 = True  # S
    if t.SNIMAC_DOLNY or t.SNIMAC_SPOMAL or t.SNIMAC_HORNY:
        t.DB_SKIP.POZ1 = False  # R
        t.DB_SKIP.POZ2 = False  # R


def automatic_up(t):
    """N6: up from the bottom when the skip is full and the mixer allows aggregate; reset at the top."""
    s = t.DB_SKIP
    if s.AUTO and t.SNIMAC_DOLNY and s.PLNY and t.DB_MIESACKA.KAMENIVO_POVOL:
        s.AUTO_HORE = True  # S
    if t.SNIMAC_HORNY:
        s.AUTO_HORE = False  # R


def dump(t):
    """N7: 6 s at the top in AUTO, then the skip is empty and the mixer has its aggregate."""
    if t.TON_V.TON(IN=t.DB_SKIP.AUTO and t.SNIMAC_HORNY, PT="6s"):
        t.DB_SKIP.PLNY = False  # R
        t.DB_MIESACKA.KAMENIVO_DODANE = True  # S


def automatic_down(t):
    """N8: down from the top once the skip is empty; reset at the bottom."""
    s = t.DB_SKIP
    if s.AUTO and t.SNIMAC_HORNY and not s.PLNY:
        s.AUTO_DOLE = True  # S
    if t.SNIMAC_DOLNY:
        s.AUTO_DOLE = False  # R


def speeds(t):
    """N9, N10: fast from the bottom to SPOMAL, slow from SPOMAL to the top, slow down, always slow in manual."""
    s = t.DB_SKIP
    t.RYCHLOST_RYCHLO = s.AUTO and t.START_HORE and (t.SNIMAC_DOLNY or s.POZ1)
    t.RYCHLOST_POMALY = (
        (s.AUTO and t.START_HORE and (t.SNIMAC_SPOMAL or s.POZ2))
        or (s.AUTO and t.START_DOLE)
        or (not s.AUTO and (t.START_HORE or t.START_DOLE))
    )


def travel_alarms(t):
    """N11, N12: an automatic ascent not at the top after 32 s, a descent not at the bottom after 45 s."""
    s = t.DB_SKIP
    if t.TON_H.TON(IN=t.START_HORE and not t.SNIMAC_HORNY, PT="32s"):
        s.ALARM_NEDOSIEL_HORE = True  # S
    if t.TON_D.TON(IN=s.AUTO and t.START_DOLE and not t.SNIMAC_DOLNY, PT="45s"):
        s.ALARM_NEDOSIEL_DOLE = True  # S


OB1 = [slow_down_alarm, directions, positions, automatic_up, dump, automatic_down, speeds, travel_alarms]
