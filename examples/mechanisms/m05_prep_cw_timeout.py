"""M-05 (seed 003, 4.3): PREP waits at most 10 s for CW; its error exit stores 12H (error 4.12)."""

PREP = MECHANISM()
CW = MECHANISM()


def interface(t):
    t.PREP.ACTIVE = t.START or t.PREP.ACTIVE


def prep(t):
    if t.PREP.begin():
        if t.PREP.step(1):
            t.CW.ACTIVE = True
            t.PREP.ex()
        if t.PREP.step(2):
            t.PREP.wait_while(t.CW.ACTIVE, timeout="10s", error="ERR1")
        if t.PREP.error("ERR1"):
            t.BZH11 = 0x12
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
