"""Small helpers that build :class:`~plcsim.plant.Drawable` shapes (mm, y up)."""

from __future__ import annotations

import math

import numpy as np

from plcsim.plant import Drawable

# A small palette, so that every rig draws in the same colours.
FRAME = (150, 150, 155)
BELT = (60, 60, 66)
BELT_RUNNING = (40, 90, 160)
DEAD_PLATE = (120, 120, 120)
END_STOP = (90, 70, 50)
BEAM_FREE = (60, 190, 60)
BEAM_CUT = (230, 40, 40)
SENSOR = (200, 200, 60)
PART = (215, 160, 60)
PART_HELD = (200, 90, 40)
PART_OFF = (170, 170, 170)
LAMP_OFF = (70, 70, 70)
LAMP_ON = (255, 200, 30)
BUTTON = (40, 120, 40)
BUTTON_PRESSED = (120, 230, 120)
TEXT = (20, 20, 20)


def pts(points) -> np.ndarray:
    """An (N, 2) float array from a sequence of (x, y)."""
    a = np.asarray(points, dtype=float).reshape(-1, 2)
    return a


def rect(x0: float, y0: float, x1: float, y1: float) -> np.ndarray:
    """The four corners of an axis-aligned rectangle, counter-clockwise."""
    return pts([(x0, y0), (x1, y0), (x1, y1), (x0, y1)])


def box(x: float, y: float, angle: float, half_length: float, half_depth: float) -> np.ndarray:
    """The four corners (4, 2) of a block centred at (x, y), turned by ``angle`` (rad), counter-clockwise from
    (-half_length, -half_depth) in its own frame.

    Plain float arithmetic into one array, not a numpy matrix product: that one goes through BLAS, whose kernels
    may fuse multiply-adds on one machine and not on another (the last bit of a measurement or a drawing would then
    depend on it), and it costs three times as much.

    >>> box(10.0, 5.0, 0.0, 2.0, 1.0).tolist()
    [[8.0, 4.0], [12.0, 4.0], [12.0, 6.0], [8.0, 6.0]]
    """
    c, s = math.cos(angle), math.sin(angle)
    lc, ls, dc, ds = half_length * c, half_length * s, half_depth * c, half_depth * s
    return np.array(  # (u, v) -> (u·c - v·s + x, u·s + v·c + y) for the corners (∓l, ∓d)
        (-lc + ds + x, -ls - dc + y, lc + ds + x, ls - dc + y, lc - ds + x, ls + dc + y, -lc - ds + x, -ls + dc + y)
    ).reshape(4, 2)


def stadium(x0: float, x1: float, y0: float, y1: float, n: int = 6) -> np.ndarray:
    """A belt outline: a rectangle [x0, x1] × [y0, y1] with half-round ends."""
    r = (y1 - y0) / 2.0
    yc = (y0 + y1) / 2.0
    out = []
    for k in range(n + 1):  # right end, bottom to top
        a = -math.pi / 2 + math.pi * k / n
        out.append((x1 - r + r * math.cos(a), yc + r * math.sin(a)))
    for k in range(n + 1):  # left end, top to bottom
        a = math.pi / 2 + math.pi * k / n
        out.append((x0 + r + r * math.cos(a), yc + r * math.sin(a)))
    return pts(out)


def polygon(path: str, points, color, text: str = "") -> Drawable:
    return Drawable(path, "polygon", pts(points), color, text=text)


def line(path: str, points, color, text: str = "") -> Drawable:
    return Drawable(path, "line", pts(points), color, text=text)


def circle(path: str, x: float, y: float, radius: float, color, text: str = "") -> Drawable:
    return Drawable(path, "circle", pts([(x, y)]), color, radius=radius, text=text)


def label(path: str, x: float, y: float, text: str, color=TEXT) -> Drawable:
    return Drawable(path, "label", pts([(x, y)]), color, text=text)


def arrow(path: str, x0: float, x1: float, y: float, color, head: float = 4.0) -> Drawable:
    """A horizontal arrow from x0 to x1 (pointing at x1), as one open polyline."""
    d = head if x1 >= x0 else -head
    return line(path, [(x0, y), (x1, y), (x1 - d, y + head * 0.6), (x1, y), (x1 - d, y - head * 0.6)], color)
