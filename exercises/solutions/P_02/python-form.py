"""P-02 in the Python form: PREP starts CW, gives it one scan, then waits for it at most 10 s."""

PREP = MECHANISM()
CW = MECHANISM()
START_M = Bool()


def interface(t):
    t.PREP.ACTIVE = (t.START and not t.START_M) or t.PREP.ACTIVE  # a press starts PREP once
    t.START_M = t.START


def prep(t):
    if t.PREP.begin():
        if t.PREP.step(1):
            t.READY = False
            t.CW.ACTIVE = True
            t.PREP.ex()
        if t.PREP.step(2):
            t.PREP.wait_while(t.CW.ACTIVE, timeout="10s", error="ERR1")
        if t.PREP.step(3):  # after the last state
            t.READY = True
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
