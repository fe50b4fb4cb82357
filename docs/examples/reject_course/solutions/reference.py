PUSH = IEC_TIMER()


def belt(t):
    if t.S1:
        t.D1 = True


def reject(t):
    t.Y1 = t.PUSH.TP(IN=t.B1, PT="400ms")


OB1 = [belt, reject]
