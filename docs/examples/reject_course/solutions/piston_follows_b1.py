def belt(t):
    if t.S1:
        t.D1 = True


def reject(t):
    t.Y1 = t.B1


OB1 = [belt, reject]
