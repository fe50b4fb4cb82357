"""M-01 (seed 003, 4.1): the classic set/hold/reset design; BUNKA is reset-dominant."""


def latch(t):
    t.BUNKA = (t.NASTAV1 or t.NASTAV2 or t.BUNKA) and not t.NULUJ


OB1 = [latch]
