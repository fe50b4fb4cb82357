"""The one clock: an integer count of nanoseconds, shared by the CPU, its timers and the scheduler."""

from __future__ import annotations

NEVER = 1 << 62
"""A time later than any simulation reaches (about 146 years of ns): "no event pending"."""


class Clock:
    """Simulated time in integer nanoseconds (never an accumulated float).

    >>> c = Clock()
    >>> c.now += 1_000_000
    >>> c.now
    1000000
    """

    __slots__ = ("now",)

    def __init__(self, now: int = 0):
        self.now = now

    def __repr__(self) -> str:
        return f"Clock(now={self.now})"
