def belt(t):
    if t.S1:
        t.D1 = True


OB1 = [belt]
