"""M-04 (seed 003, 4.3): the preparatory functions (mechanism PREP) start CW and wait for it."""

PREP = MECHANISM()
CW = MECHANISM()


def interface(t):
    t.PREP.ACTIVE = t.START or t.PREP.ACTIVE


def prep(t):
    if t.PREP.begin():
        if t.PREP.step(1):
            t.CW.ACTIVE = True
            t.PREP.ex()  # without it, CW would be set again in every scan of the wait
        if t.PREP.step(2):
            t.PREP.wait_while(t.CW.ACTIVE)
        t.PREP.end()


def cw(t):
    if t.CW.begin():
        if t.CW.step(1):
            t.SMN = False
            t.CW.wait_while(t.KSMN)
        if t.CW.step(2):
            t.SMP = True
            t.CW.wait_until(t.KSMP)
        t.CW.end()


OB1 = [interface, prep, cw]
