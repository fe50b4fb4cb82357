"""The resource limits of a grading child: CPU time, memory and wall time, checked when given.

The child applies the CPU-time and memory limits to itself (:mod:`plcsim.grading.sandbox.confine`);
the grader stops it at the wall-time limit, and watches what the system does not enforce from outside
(:mod:`plcsim.grading.sandbox.watchdog`).
"""

from __future__ import annotations

from dataclasses import dataclass

from plcsim.core.errors import ConfigurationError


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
