"""M-02 (seed 003, the flowchart figure): mechanism NAZEV in the Python form."""

NAZEV = MECHANISM()


def interface(t):
    t.NAZEV.ACTIVE = t.START or t.NAZEV.ACTIVE


def nazev(t):
    if t.NAZEV.begin():
        if t.NAZEV.step(1):  # ACTION 1, STATE 1
            t.HYDRAULIKA = True
            t.NAZEV.wait_until(t.KONTAKT1 and t.KONTAKT2)
        if t.NAZEV.step(2):  # ACTION 2, STATE 2
            t.POHON = False
            t.NAZEV.wait_while(t.KONTAKT3)
        t.NAZEV.end()


OB1 = [interface, nazev]
