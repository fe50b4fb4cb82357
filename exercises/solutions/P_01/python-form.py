"""P-01 in the Python form: the same mechanism, a step per state."""

CWCCW = MECHANISM()


def interface(t):
    t.CWCCW.ACTIVE = t.REV or t.CWCCW.ACTIVE


def cwccw(t):
    if t.CWCCW.begin():
        if t.CWCCW.step(1):
            t.SMP = False
            t.CWCCW.wait_while(t.KSMP, timeout="1s", error="CW_ERR", code=4)
        if t.CWCCW.step(2):
            t.CWCCW.delay("200ms")
        if t.CWCCW.step(3):
            t.SMN = True
            t.CWCCW.wait_until(t.KSMN, timeout="1s", error="CW_ERR", code=5)
        if t.CWCCW.error("CW_ERR"):
            t.SMN = False
            t.BZH11 = t.CWCCW.ERR
        t.CWCCW.end()


OB1 = [interface, cwccw]
