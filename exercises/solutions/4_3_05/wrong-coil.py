"""A typical slip (not from the textbook): D1 as a plain coil of S1.

The belt runs only while the object is still in front of S1 and stops as soon as it has left
the beam, far from S2.
"""


def OB1(t):
    t.D1 = t.S1 and not t.S2
