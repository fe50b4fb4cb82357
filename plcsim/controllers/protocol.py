"""What the simulation drives: a controller, whichever family (the S7-1200 CPU, the Tecomat NS950).

:class:`plcsim.sim.simulation.Simulation`, the recorder, the wiring and the scenario actions use only this surface:
inputs and outputs by tag name, ``run_until`` on the one clock, the scan hooks the recorder subscribes
to, a tag table (names, %I/%Q areas, elementary types) and a namespace ``t`` of the values traced. A
front end whose programs run on a controller of their own offers ``controller(tags, **options)``;
:func:`plcsim.controllers.choice.controller_for` picks it, and the S7 CPU otherwise. Why the Tecomat is a
controller of its own rather than a profile inside the S7 runtime, and what the two share:
``docs/architecture.md``.
"""

from __future__ import annotations

from collections import deque
from dataclasses import dataclass
from typing import Any, Protocol

from plcsim.core.clock import Clock
from plcsim.core.literals import format_ns
from plcsim.core.observers import Subscribers
from plcsim.tags.table import TagTable

RUN = "RUN"
STOP = "STOP"
"""A controller's two modes (``cpu.mode``)."""


@dataclass(frozen=True)
class DiagnosticEntry:
    """One entry of a controller's diagnostic buffer (``cpu.diagnostics``)."""

    time_ns: int
    event: str
    message: str
    task: str | None = None
    network: str | None = None
    line: int | None = None

    def __str__(self) -> str:
        where = ""
        if self.task:
            where = (
                f" [{self.task}"
                + (f" network {self.network}" if self.network else "")
                + (f", line {self.line}" if self.line else "")
                + "]"
            )
        return f"{format_ns(self.time_ns)}: {self.event}{where}: {self.message}"


class Controller(Protocol):
    """The surface of a CPU the simulation, the recorder, the wiring and the scenario actions use."""

    clock: Clock
    config: Any
    """``cycle_ns``, ``timer_dialect`` and ``rtc_start`` are read for the trace's notes."""
    mode: str
    table: TagTable
    t: Any
    """The traced values as attributes (``t.__dict__[name]``)."""
    system_tags: frozenset[str]
    """Tags the controller keeps itself (the S7's clock and system memory bits): the default trace leaves
    them out unless the program uses them."""
    inputs: dict[str, Any]
    """The input terminals by tag name; the wiring writes them before each step."""
    outputs: dict[str, Any]
    """What the output modules drive, by tag name (all off in STOP)."""
    image_in: dict[str, Any]
    """Each input as the last sample of the process image read it (what the trace records)."""
    output_version: int
    scan_count: int
    scan_start_ns: int
    scan_end_ns: int
    scan_task_number: int
    task_numbers: dict[str, int]
    scan_end: Subscribers
    task_end: Subscribers
    cut: Subscribers
    diagnostics: deque
    warnings: list[str]
    program: Any
    loaded: Any
    compiled: Any
    """The Python front end's compiled program (its static analysis); None for another front end."""

    @property
    def error(self) -> Any: ...

    def run_until(self, until_ns: int) -> None: ...

    def next_event_ns(self) -> int: ...

    def set_input(self, name: str, value: Any) -> None: ...

    def write(self, name: str, value: Any) -> None: ...

    def start(self) -> None: ...

    def stop(self, reason: str = "requested") -> None: ...

    def power_cycle(self) -> None: ...
