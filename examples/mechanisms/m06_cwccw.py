"""M-06 (seed 003, 4.3): CWCCW without time limits, in the Python form."""

CWCCW = MECHANISM()


def interface(t):
    t.CWCCW.ACTIVE = t.START or t.CWCCW.ACTIVE


def cwccw(t):
    if t.CWCCW.begin():
        if t.CWCCW.step(1):
            t.SMP = False
            t.CWCCW.wait_while(t.KSMP)
        if t.CWCCW.step(2):
            t.CWCCW.delay("200ms")
        if t.CWCCW.step(3):
            t.SMN = True
            t.CWCCW.wait_until(t.KSMN)
        t.CWCCW.end()


OB1 = [interface, cwccw]
