"""P-02 in the Python form: PREP starts CW, gives it one scan, then waits for it at most 10 s; CW retries a
contactor that does not pick up (its steps 10 and 11, reached by goto from the error branch)."""

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
            t.CW.wait_until(t.KSMP, timeout="2s", error="RETRY")
        if t.CW.error("RETRY"):  # it did not pick up: off, 0.5 s, and again
            t.SMP = False
            t.CW.goto(10)
        if t.CW.step(10):
            t.CW.delay("500ms")
        if t.CW.step(11):
            t.CW.goto(2)
        t.CW.end()


OB1 = [interface, prep, cw]
