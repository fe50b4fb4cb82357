"""The resource limits of a grading child: CPU time, memory and wall time, checked when given, and the
CPU budget fitted to an exercise.

The child applies the CPU-time and memory limits to itself (:mod:`plcsim.grading.sandbox.confine`);
the grader stops it at the wall-time limit, and watches what the system does not enforce from outside
(:mod:`plcsim.grading.sandbox.watchdog`).

The absolute limits (60 s of CPU) bound any submission; an exercise whose reference grades in about a
second needs far less. A :class:`Budget` is a generous multiple of the reference's measured CPU time
(:data:`MULTIPLE`, never below :data:`FLOOR_S`), or what the exercise sets itself
(``Exercise.cpu_budget_s``). A submission over it is *too slow for this exercise*, its own outcome,
distinct from a time limit and from a crash.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from plcsim.core.errors import ConfigurationError

MULTIPLE = 10
"""A submission may use this many times the CPU time the reference used, in the same kind of child."""
FLOOR_S = 10
"""The least CPU budget, in seconds: a tiny exercise's reference measures in noise, and the grader's own
load must never be charged to the student."""


@dataclass(frozen=True)
class Budget:
    """The CPU seconds a submission of one exercise may use: fitted to the reference's measured cost
    (``reference_cpu_s``) or set by the exercise (``reference_cpu_s`` None).

    >>> Budget.fitted(1.3).cpu_seconds, Budget.fitted(0.2).cpu_seconds
    (13, 10)
    >>> print(Budget.fitted(1.3).too_slow().replace(" (", "\\n("))
    too slow for this exercise: it used more than 10× the reference's CPU time
    (the reference 1.30 s, the budget 13 s)
    >>> print(Budget.fitted(0.0).too_slow().replace(" (", "\\n("))
    too slow for this exercise: it used more than the budget fitted to the reference
    (the reference 0.00 s, the budget 10 s)
    """

    cpu_seconds: int
    reference_cpu_s: float | None = None

    @classmethod
    def fitted(cls, reference_cpu_s: float) -> Budget:
        """:data:`MULTIPLE` times the reference's CPU seconds, at least :data:`FLOOR_S`."""
        return cls(max(FLOOR_S, math.ceil(MULTIPLE * reference_cpu_s)), reference_cpu_s)

    @classmethod
    def of_exercise(cls, seconds: float) -> Budget:
        return cls(max(1, math.ceil(seconds)))

    def too_slow(self) -> str:
        """What a submission stopped at this budget is told."""
        if self.reference_cpu_s is None:
            budget = f"the exercise's budget of {self.cpu_seconds} s of CPU time"
            return f"too slow for this exercise: it used more than {budget}"
        figures = f"(the reference {self.reference_cpu_s:.2f} s, the budget {self.cpu_seconds} s)"
        if not self.reference_cpu_s:  # under one tick of the thread clock (about 16 ms on Windows): no multiple
            return f"too slow for this exercise: it used more than the budget fitted to the reference {figures}"
        times = self.cpu_seconds / self.reference_cpu_s
        return f"too slow for this exercise: it used more than {times:.0f}× the reference's CPU time {figures}"


@dataclass
class Limits:
    """Resource limits of the child process that runs a submission; each must be positive.

    >>> Limits(cpu_seconds=-1)
    Traceback (most recent call last):
    ...
    plcsim.core.errors.ConfigurationError: the CPU-time limit must be a positive whole number of seconds, got -1 ...
    """

    cpu_seconds: int = 60
    memory_mb: int = 2048
    wall_seconds: float = 120.0
    budget: Budget | None = None
    """The exercise's CPU budget; the child is stopped at it when it is below ``cpu_seconds``."""

    @property
    def cpu_limit(self) -> int:
        """The CPU seconds the child may use: the budget where it binds, else ``cpu_seconds``."""
        return min(self.cpu_seconds, self.budget.cpu_seconds) if self.budget else self.cpu_seconds

    @property
    def budget_binds(self) -> bool:
        """True if the child is stopped at the exercise's budget, not at the absolute limit."""
        return self.budget is not None and self.budget.cpu_seconds < self.cpu_seconds

    def __post_init__(self) -> None:
        if isinstance(self.cpu_seconds, bool) or not isinstance(self.cpu_seconds, int) or self.cpu_seconds < 1:
            raise ConfigurationError(
                f"the CPU-time limit must be a positive whole number of seconds, got {self.cpu_seconds!r} "
                f"(--cpu-seconds 60); a limit cannot be switched off"
            )
        if isinstance(self.memory_mb, bool) or not isinstance(self.memory_mb, int) or self.memory_mb < 64:
            raise ConfigurationError(
                f"the memory limit must be a whole number of at least 64 MB, got {self.memory_mb!r} (--memory-mb 2048)"
            )
        if not isinstance(self.wall_seconds, int | float) or not self.wall_seconds > 0:
            raise ConfigurationError(
                f"the wall-time limit must be a positive number of seconds, got {self.wall_seconds!r}"
            )
