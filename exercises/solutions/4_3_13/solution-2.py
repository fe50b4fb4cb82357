"""4.3.13, solution 2: the counter replaced by ADD and MOVE on an Int variable.

POCET (count; the textbook does not name it) := POCET + 1 on each timer expiry, MOVE 0 -> POCET
while STROJ_START is FALSE; STROJ_KONIEC := POCET >= 3. The rest as in solution 1 (ON 1 s, OFF 2 s).
"""

TON_S = IEC_TIMER()
POCET = Int(0)


def cycle(t):
    """Network 1: the 3 s cycle timer; on expiry add one cycle and restart the timer."""
    if t.TON_S.TON(IN=t.STROJ_START and not t.STROJ_KONIEC, PT="3s"):
        t.POCET = t.POCET + 1  # ADD
        RT(t.TON_S)


def reset_count(t):
    """Network 2: MOVE 0 to the count while the machine is not allowed to run."""
    if not t.STROJ_START:
        t.POCET = 0  # MOVE


def finished(t):
    """Network 3: the sequence is finished after three cycles."""
    t.STROJ_KONIEC = t.POCET >= 3


def machine(t):
    """Network 4: the machine runs in the first second of each cycle."""
    t.STROJ_ZAP = t.STROJ_START and not t.STROJ_KONIEC and t.TON_S.ET < TIME("1s")


OB1 = [cycle, reset_count, finished, machine]
