"""4.3.13, solution 1 as the task states it: ON for 1 s, then OFF for 2 s, three times.

A 3 s timer runs while STROJ_START is set and the sequence is not finished; each expiry counts one
cycle (CTU, PV = 3) and restarts the timer (RT). The machine runs while the timer's ET is below 1 s.
STROJ_START going FALSE resets the counter and with it STROJ_KONIEC ("from a suitable condition").

The textbook's solution text compares ET >= 1 s (off 1 s, then on 2 s); that contradicts the task,
which is normative here (see textbook-variant.py). The counter sits on the timer's Q pin in the same
network as RT: a later network reading TON_S.Q would see the timer already reset (wrong-rt-first.py).
"""

TON_S = IEC_TIMER()
CTU_S = IEC_COUNTER()


def cycle(t):
    """Network 1: the 3 s cycle timer; on expiry count one cycle and restart the timer."""
    q = t.TON_S.TON(IN=t.STROJ_START and not t.STROJ_KONIEC, PT="3s")
    t.STROJ_KONIEC = t.CTU_S.CTU(CU=q, R=not t.STROJ_START, PV=3)
    if q:
        RT(t.TON_S)


def machine(t):
    """Network 2: the machine runs in the first second of each cycle."""
    t.STROJ_ZAP = t.STROJ_START and not t.STROJ_KONIEC and t.TON_S.ET < TIME("1s")


OB1 = [cycle, machine]
