"""The S7 CPU's hardware configuration and simulator options, and its clock and system memory bits."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field

from plcsim.controllers.s7.instructions.timers import TimerDialect
from plcsim.core.errors import ConfigurationError
from plcsim.core.literals import datetime_literal, to_ns
from plcsim.tags.aliasing import MemoryLayout

CLOCK_BITS = (  # bit, name, half period in ms (S7-1200 clock memory byte layout)
    (0, "Clock_10Hz", 50),
    (1, "Clock_5Hz", 100),
    (2, "Clock_2_5Hz", 200),
    (3, "Clock_2Hz", 250),
    (4, "Clock_1_25Hz", 400),
    (5, "Clock_1Hz", 500),
    (6, "Clock_0_625Hz", 800),
    (7, "Clock_0_5Hz", 1000),
)
SYSTEM_BITS = ((0, "FirstScan"), (1, "DiagStatusUpdate"), (2, "AlwaysTRUE"), (3, "AlwaysFALSE"))


@dataclass
class CPUConfig:
    """Hardware configuration and simulator options of one CPU.

    Attributes:
        cycle: OB1 cycle time (fixed-cycle model), default 1 ms.
        min_cycle: minimum cycle time; a shorter cycle waits.
        jitter: seeded uniform jitter of the cycle, +-jitter.
        network_cost: if set, the cost of each OB1 network; the cycle is then N * network_cost
            (at least ``min_cycle``) instead of ``cycle``.
        interrupt_duration: execution time of a cyclic-interrupt OB (the textbook: about 1 ms).
        periods: OB periods set in the hardware configuration, e.g. ``{"OB30": "1s"}``; a program's
            ``CyclicInterrupt(period=...)`` wins.
        seed: seed of the jitter.
        timer_dialect: ``s7_1200`` (Q/ET refresh when read, the textbook) or ``iec`` (only at the box).
        textbook_strict_timers: a timer whose Q and ET are used nowhere does not start (§3.6.1).
        counter_overflow: ``wrap`` (the textbook) or ``saturate`` (IEC/S7-300).
        clock_memory_byte: enable clock memory at MB<n> (Clock_10Hz .. Clock_0_5Hz; Clock_1Hz = bit 5).
        system_memory_byte: enable system memory at MB<n> (FirstScan, DiagStatusUpdate, AlwaysTRUE,
            AlwaysFALSE).
        retentive_markers: number of %M bytes from MB0 that are retentive.
        watchdog_iterations: loop iterations (and jumps) one task execution may make before the
            cycle watchdog sends the CPU to STOP, a deterministic stand-in for the 150 ms monitoring time.
        rtc_start: the CPU's local date and time at simulated time 0 (for RD_LOC_T).
        family: ``S7-1200`` or ``S7-1500`` (SCALE/UNSCALE exist only on the S7-1500).
        memory: sizes of %I, %Q and %M.
        input_writes: what a program storing into an input tag (%I) gets when it is loaded: ``warn``
            (a load warning naming the line; the store changes only the program's process image) or
            ``error`` (the program is refused).
        mechanism_mode: how a MECHANISM advances: ``plc836`` (the chapter: every state whose condition
            holds passes in the same scan) or ``iec`` (IEC 61131-3 SFC: at most one step per scan).
        fuse: run a scan that nothing can interrupt in one call (:mod:`plcsim.controllers.s7.fused`);
            False takes the general scan loop for every scan (the tests compare the two).
    """

    cycle: str | int = "1ms"
    min_cycle: str | int | None = None
    jitter: str | int = 0
    network_cost: str | int | None = None
    interrupt_duration: str | int = "1ms"
    periods: Mapping[str, str | int] = field(default_factory=dict)
    seed: int = 0
    timer_dialect: TimerDialect | str = TimerDialect.S7_1200
    textbook_strict_timers: bool = True
    counter_overflow: str = "wrap"
    clock_memory_byte: int | None = None
    system_memory_byte: int | None = None
    retentive_markers: int = 0
    watchdog_iterations: int = 1_000_000
    rtc_start: str = "DTL#2026-01-05-08:00:00"
    family: str = "S7-1200"
    memory: MemoryLayout = field(default_factory=MemoryLayout)
    input_writes: str = "warn"
    mechanism_mode: str = "plc836"
    fuse: bool = True

    def __post_init__(self) -> None:
        try:
            self.timer_dialect = TimerDialect(self.timer_dialect)
        except ValueError:
            raise ConfigurationError(f"timer_dialect {self.timer_dialect!r}: use 's7_1200' or 'iec'") from None
        if self.counter_overflow not in ("wrap", "saturate"):
            raise ConfigurationError(f"counter_overflow {self.counter_overflow!r}: use 'wrap' or 'saturate'")
        if self.input_writes not in ("warn", "error"):
            raise ConfigurationError(f"input_writes {self.input_writes!r}: use 'warn' or 'error'")
        if self.mechanism_mode not in ("plc836", "iec"):
            raise ConfigurationError(f"mechanism_mode {self.mechanism_mode!r}: use 'plc836' or 'iec'")
        if self.family not in ("S7-1200", "S7-1500"):
            raise ConfigurationError(f"family {self.family!r}: use 'S7-1200' or 'S7-1500'")
        self.cycle_ns = to_ns(self.cycle, "cycle")
        if self.cycle_ns <= 0:
            raise ConfigurationError(f"cycle {self.cycle!r} must be positive")
        self.min_cycle_ns = 0 if self.min_cycle is None else to_ns(self.min_cycle, "min_cycle")
        self.jitter_ns = to_ns(self.jitter, "jitter")
        if self.jitter_ns < 0 or self.jitter_ns >= self.cycle_ns:
            raise ConfigurationError(f"jitter {self.jitter!r} must lie in 0 .. cycle")
        self.network_cost_ns = None if self.network_cost is None else to_ns(self.network_cost, "network_cost")
        self.interrupt_duration_ns = to_ns(self.interrupt_duration, "interrupt_duration")
        for byte in (self.clock_memory_byte, self.system_memory_byte):
            if byte is not None and not 0 <= byte < self.memory.markers:
                raise ConfigurationError(f"memory byte {byte} lies outside %M (0..{self.memory.markers - 1})")
        if self.clock_memory_byte is not None and self.clock_memory_byte == self.system_memory_byte:
            raise ConfigurationError(
                f"clock and system memory both at MB{self.clock_memory_byte}; they must not overlap "
                f"(TIA defaults: clock MB0, system MB1; textbook erratum §4.3.8)"
            )
        datetime_literal(self.rtc_start)
