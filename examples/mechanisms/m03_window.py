"""M-03 (seed 003, fig. 4.3) completed: VYST1 is in the window of step 2, rewritten every scan it waits."""

MCH = MECHANISM()
ALARM = Bool()


def mch(t):
    if t.MCH.begin():
        if t.MCH.step(1):
            t.MCH.wait_until(t.VST1)
        if t.MCH.step(2):
            t.VYST1 = True
            t.MCH.wait_while(t.VST1 and t.VST2, timeout="2s", error="ERR")
        if t.MCH.step(3):  # the actions after the last state: no state of their own
            t.VYST1 = False
        if t.MCH.error("ERR"):
            t.ALARM = True
        t.MCH.end()


OB1 = [mch]
