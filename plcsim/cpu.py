"""The CPU: RUN/STOP, tasks and priorities, process images, retain, clock and system memory,
the cycle watchdog and the diagnostic buffer, on the one integer clock.

Timing model (documented choice; the textbook leaves the details open):

* **OB1** runs again as soon as it ends. One execution ("scan") lasts the cycle time ``D`` of the
  scan-time model (default 1 ms): inputs are read into the process image at its start ``t0``, its
  networks run one after the other at ``t0``, and the output image is written at ``t0 + D``. The
  network boundaries sit at ``t0 + k*D/N`` (spread evenly; or ``k*network_cost``): they are where a
  due interrupt comes between two networks. An HMI write during a scan is seen by the next scan.
* **Cyclic interrupts** (OB30..OB38) are due at ``start + phase + k*period``. A due interrupt of
  higher priority pre-empts a running OB **between networks**: it runs at its due time, and the
  interrupted OB's remaining networks and its end move later by the interrupt's duration
  (``interrupt_duration``, default 1 ms as in the textbook's OB30 examples). An OB with one network is
  therefore atomic. An interrupt refreshes only the inputs its networks use and writes only the
  outputs they use (its process-image partition); OB1 refreshes and writes all.
* **OB100** runs at the STOP->RUN instant, before OB1 and before the first interrupt call.
* Every network of one execution sees the execution's start time ``t0`` (later by the time an
  interrupt pre-empted it), however the host steps the clock: timers count in whole scans.

>>> cpu = CPU(program="def OB1(t):\\n    t.LED = t.TL\\n",
...           tags={"TL": Tag("%I0.0"), "LED": Tag("%Q0.0")})
>>> cpu.set_input("TL", True)
>>> cpu.scan()
>>> cpu.outputs["LED"]
True
"""

from __future__ import annotations

import datetime as _dt
import operator
import random
import traceback
from bisect import bisect_left
from collections import deque
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field, replace
from typing import Any

from plcsim.clock import Clock
from plcsim.compiler import FB_STORE, STORE, TICK
from plcsim.errors import ConfigurationError, PlcError, PlcTypeError, UnknownTagError, did_you_mean
from plcsim.instructions import FB_WRITABLE
from plcsim.instructions.counters import IecCounter
from plcsim.instructions.edges import EdgeTrigger, bit_resolver, make_edge_instructions
from plcsim.instructions.system import JumpTo, ReturnFromBlock, dtl_of, make_move, make_rd_loc_t
from plcsim.instructions.timers import IecTimer, TimerDialect, preset_ms
from plcsim.literals import datetime_literal, format_ns, to_ns
from plcsim.memory import Address, ByteMemory, parse_address
from plcsim.program import CompiledProgram, Program, TaskSpec, runtime_namespace
from plcsim.tags import (
    MemoryLayout,
    PlcArray,
    PlcStruct,
    Tag,
    TagTable,
    build_runtime,
    non_optimized_offsets,
    reset_to_start,
    store,
)
from plcsim.types import Bool, ElementaryType, Int

RUN = "RUN"
STOP = "STOP"

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


class CycleWatchdog(Exception):  # noqa: N818 - it is the S7 name of the event
    """The program looped inside one task execution past the watchdog budget."""


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

    def __post_init__(self) -> None:
        try:
            self.timer_dialect = TimerDialect(self.timer_dialect)
        except ValueError:
            raise ConfigurationError(f"timer_dialect {self.timer_dialect!r}: use 's7_1200' or 'iec'") from None
        if self.counter_overflow not in ("wrap", "saturate"):
            raise ConfigurationError(f"counter_overflow {self.counter_overflow!r}: use 'wrap' or 'saturate'")
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


@dataclass(frozen=True)
class DiagnosticEntry:
    """One entry of the diagnostic buffer."""

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


class _Task:
    """A task of the running program (an OB with its networks and process-image partition)."""

    __slots__ = (
        "spec",
        "name",
        "kind",
        "priority",
        "networks",
        "titles",
        "labels",
        "period_ns",
        "phase_ns",
        "duration_ns",
        "next_due",
        "inputs",
        "outputs",
        "offsets",
        "n",
        "execution",
        "merged",
        "spans",
    )

    def __init__(
        self,
        spec: TaskSpec,
        networks: list[Callable[[Any], None]],
        merged: Callable[[Any], None] | None = None,
        spans: list[tuple[int, int]] | None = None,
    ):
        self.spec, self.name, self.kind, self.priority = spec, spec.name, spec.kind, spec.priority
        self.networks = networks
        self.merged = merged
        self.spans = spans or []
        self.n = len(networks)
        self.titles = [n.name for n in spec.networks]
        self.labels = {n.label: i for i, n in enumerate(spec.networks) if n.label}
        self.period_ns, self.phase_ns = spec.period_ns, spec.phase_ns
        self.duration_ns = spec.duration_ns
        self.next_due = 0
        self.inputs: list[str] = []
        self.outputs: list[str] = []
        self.offsets: dict[int, list[int]] = {}
        self.execution = _Execution(self)

    def network_offsets(self, duration: int, cost: int | None) -> list[int]:
        """Where in an execution of ``duration`` each network sits (for pre-emption between networks)."""
        offsets = self.offsets.get(duration)
        if offsets is None:
            n = self.n
            offsets = [k * cost for k in range(n)] if cost else [(k * duration) // n for k in range(n)]
            self.offsets[duration] = offsets
        return offsets


class _Execution:
    """The running execution of a task: start, duration, next network, time lost to pre-emption."""

    __slots__ = ("task", "t0", "duration", "offsets", "index", "shift", "paused_at")

    def __init__(self, task: _Task):
        self.task = task
        self.t0 = self.duration = self.index = self.shift = 0
        self.paused_at = -1
        self.offsets: list[int] = []

    def next_time(self) -> int:
        if self.index < self.task.n:
            return self.t0 + self.shift + self.offsets[self.index]
        return self.t0 + self.shift + self.duration


class CPU:
    """A simulated S7-1200 CPU running one program on the one clock.

    Args:
        tags: the tag table (an exercise's I/O table); a mapping ``name -> Tag(...)`` is accepted.
        program: a :class:`Program`, program source text, or None (load later).
        config: a :class:`CPUConfig`; keyword ``options`` build one instead.
        start: switch to RUN after loading the program (as after a download and a mode switch).

    Physical I/O: write sensor values into :attr:`inputs` (or :meth:`set_input`); read what the output
    modules drive from :attr:`outputs` (all off in STOP).
    """

    def __init__(
        self,
        tags: TagTable | Mapping[str, Any] | None = None,
        program: Program | str | None = None,
        config: CPUConfig | None = None,
        *,
        start: bool = True,
        clock: Clock | None = None,
        **options: Any,
    ):
        if config is not None and options:
            raise ConfigurationError("give either config=CPUConfig(...) or keyword options, not both")
        self.config = config or CPUConfig(**options)
        self.clock = clock or Clock()
        self.timer_dialect = self.config.timer_dialect
        self.counter_overflow = self.config.counter_overflow
        self.base_table = self._system_table(tags)
        self.mode = STOP
        self.diagnostics: deque[DiagnosticEntry] = deque(maxlen=1000)
        self.inputs: dict[str, Any] = {}
        self.outputs: dict[str, Any] = {}
        self.forces: dict[str, Any] = {}
        self.on_scan_end: Callable[[CPU], None] | None = None
        self.on_task_end: Callable[[CPU, str, int, int], None] | None = None
        self.scan_count = 0
        self.scan_start_ns = 0
        self.scan_end_ns = 0
        self.output_version = 0
        self.program: Program | None = None
        self.compiled: CompiledProgram | None = None
        self.warnings: list[str] = []
        self._rng = random.Random(self.config.seed)
        self._stack: list[_Execution] = []
        self._tasks: list[_Task] = []
        self._ob1: _Task | None = None
        self._interrupts: list[_Task] = []
        self._next_irq = _NEVER
        self._ob1_next = 0
        self._first_scan = False
        self._diag_changed = False
        self._clock_next = 0
        self._ticks = [0]
        self.t: PlcStruct = PlcStruct(self.base_table.schema(), "t")
        self._load_table(self.base_table, None)
        if program is not None:
            self.load(program)
            if start:
                self.start()

    # -- tag table ----------------------------------------------------------------------------

    def _system_table(self, tags: TagTable | Mapping[str, Any] | None) -> TagTable:
        if isinstance(tags, TagTable):
            table = tags.copy()
        else:
            table = TagTable()
            for name, decl in (tags or {}).items():
                table.add(name, decl, source="tag table")
        cfg = self.config
        if cfg.clock_memory_byte is not None:
            for bit, name, _ in CLOCK_BITS:
                if name not in table:
                    table.add(name, Tag(f"%M{cfg.clock_memory_byte}.{bit}"), source="clock memory")
        if cfg.system_memory_byte is not None:
            for bit, name in SYSTEM_BITS:
                if name not in table:
                    table.add(name, Tag(f"%M{cfg.system_memory_byte}.{bit}"), source="system memory")
        if cfg.retentive_markers:
            for name, entry in list(table.entries.items()):
                addr = entry.address
                if addr is not None and addr.area == "M" and addr.byte < cfg.retentive_markers:
                    table.entries[name] = replace(entry, member=replace(entry.member, retain=True))
        return table

    def _load_table(self, table: TagTable, extra_addresses: list[str] | None) -> None:
        table = table.copy()
        for text in extra_addresses or []:
            addr = parse_address(text)
            key = str(addr)
            if key not in table:
                table.add(key, Tag(key, addr.default_type()), source="absolute address")
        self.table = table
        self.t, self.memories, self.aliases = build_runtime(table, self, self.config.memory)
        self._cells = [(self.t, e.name, e.address, e.member.type) for e in table if e.address is not None]
        numbers = table.db_numbers()
        for e in table:  # members of non-optimized DBs, so that peek() composes %DBn.DB... from them
            if e.db is not None and not e.db.optimized:
                offsets = non_optimized_offsets(e.member.type)  # type: ignore[arg-type]
                offsets.pop("__size__")
                for key, (off, dtype) in offsets.items():
                    addr = Address("DB", off.byte, off.bit, off.bits, numbers[e.name])
                    self._cells.append((self.t.__dict__[e.name], key, addr, dtype))
        self.input_names = [e.name for e in table if e.address is not None and e.address.area == "I"]
        self.output_names = [e.name for e in table if e.address is not None and e.address.area == "Q"]
        self.inputs = {name: self.inputs.get(name, self.t.__dict__[name]) for name in self.input_names}
        self.outputs = {name: _off(self.t.__dict__[name]) for name in self.output_names}
        aliased = {c.key for c in self.aliases if c.container is self.t}
        self._aliased_inputs = [n for n in self.input_names if n in aliased]
        self._plain_inputs = [n for n in self.input_names if n not in aliased]
        # the input terminals of overlapping input tags (%IW64 and %I65.0) are one memory too
        self._input_cells = {c.key: c for c in self.aliases if c.container is self.t and c.key in self.inputs}
        self._terminals = ByteMemory("I", self.config.memory.inputs)
        for name, cell in self._input_cells.items():
            self._terminals.write(cell.address, cell.dtype, self.inputs[name])
        self._out_getter = _getter(self.output_names)
        self._last_out: tuple[Any, ...] = tuple(self.outputs[n] for n in self.output_names)
        if self.config.retentive_markers:
            self._retentive_m = bytes(self.memories[("M", None)].data[: self.config.retentive_markers])

    # -- loading ------------------------------------------------------------------------------

    def load(self, program: Program | str) -> None:
        """Download a program (the CPU goes to STOP; call :meth:`start` for RUN)."""
        if isinstance(program, str):
            program = Program.from_source(program)
        was_running = self.mode == RUN
        self.stop(reason="download")
        table = program.declare_into(self.base_table)
        self._load_table(table, _address_strings(program))
        aliased = frozenset(c.key if c.container is self.t else f"{c.container._path}.{c.key}" for c in self.aliases)
        compiled = program.compile(
            self.table, aliased, strict_timers=self.config.textbook_strict_timers, family=self.config.family
        )
        namespace = runtime_namespace(compiled, self._bound_instructions())
        exec(compiled.code, namespace)
        self.program, self.compiled, self.warnings = program, compiled, compiled.warnings
        for path in compiled.inert_timers:
            timer = self._resolve_value(path.split(".", 1)[1] if "." in path else path)
            if isinstance(timer, IecTimer):
                timer._inert = True
        tasks = []
        for name, spec in program.tasks.items():
            if spec.kind == "interrupt":
                period = self.config.periods.get(name)
                if period is not None and not _period_given(program, name):
                    spec.period_ns = to_ns(period, f"{name} period")
            merged = compiled.merged.get(name)
            spans = [
                (program.functions[n.name].lineno, program.functions[n.name].end_lineno or 0) for n in spec.networks
            ]
            task = _Task(spec, [namespace[n.name] for n in spec.networks], namespace[merged] if merged else None, spans)
            used: set[str] = set()
            for net in spec.networks:
                used |= compiled.analysis.tags_used(net.name)
            if spec.kind == "cyclic":
                task.inputs, task.outputs = list(self.input_names), list(self.output_names)
            else:
                task.inputs = [n for n in self.input_names if n in used]
                task.outputs = [n for n in self.output_names if n in used]
            if task.duration_ns is None:
                task.duration_ns = self.config.interrupt_duration_ns if spec.kind == "interrupt" else 0
            tasks.append(task)
        self._tasks = tasks
        self._ob1 = next((t for t in tasks if t.kind == "cyclic"), None) or _Task(TaskSpec("OB1", "cyclic", []), [])
        self._ob1.inputs, self._ob1.outputs = list(self.input_names), list(self.output_names)
        self._interrupts = sorted((t for t in tasks if t.kind == "interrupt"), key=lambda t: -t.priority)
        self._startup = [t for t in tasks if t.kind == "startup"]
        self._diag("download", f"program {program.filename} loaded: {', '.join(program.tasks) or 'no OBs'}")
        if was_running:
            self.start()

    def _bound_instructions(self) -> dict[str, Any]:
        lookup = bit_resolver(self.t, self.resolve_path)
        bound: dict[str, Any] = make_edge_instructions(lookup)
        bound["MOVE"] = make_move(self.resolve_path)
        bound["RD_LOC_T"] = make_rd_loc_t(self.local_time)
        ticks = self._ticks
        budget = self.config.watchdog_iterations

        def tick() -> None:
            ticks[0] += 1
            if ticks[0] > budget:
                raise CycleWatchdog()

        bound[TICK] = tick
        bound[STORE] = _store_any
        bound[FB_STORE] = _fb_store
        return bound

    # -- modes --------------------------------------------------------------------------------

    def start(self) -> None:
        """STOP -> RUN: non-retain tags take their start values, OB100 runs, then OB1 and the interrupts."""
        if self.mode == RUN:
            return
        if self.program is None:
            raise ConfigurationError("no program is loaded; call cpu.load(program) first")
        now = self.clock.now
        if self.config.retentive_markers:
            # what the retentive %M bytes hold now (a tag that overlaps no other keeps its value only in t)
            memory = self.memories[("M", None)]
            for container, key, addr, dtype in self._cells:
                if addr.area == "M" and addr.byte < self.config.retentive_markers:
                    memory.write(addr, dtype, container.__dict__[key])
            self._retentive_m = bytes(memory.data[: self.config.retentive_markers])
        reset_to_start(self.t)
        if self.config.retentive_markers:
            self.memories[("M", None)].data[: self.config.retentive_markers] = self._retentive_m
            for container, key, addr, dtype in self._cells:
                if addr.area == "M" and addr.byte < self.config.retentive_markers:
                    container.__dict__[key] = self.memories[("M", None)].read(addr, dtype)
        self.mode = RUN
        self._diag("STOP->RUN", "the CPU switched to RUN")
        self._stack.clear()
        self._first_scan = True
        self._set_system_bits()
        self._clock_next = 0
        for task in self._interrupts:
            task.next_due = now + task.phase_ns
        self._next_irq = min((t.next_due for t in self._interrupts), default=_NEVER)
        self._ob1_next = now
        for task in self._startup:
            self._run_atomic(task, now)
            if self.mode != RUN:
                return

    def stop(self, reason: str = "requested") -> None:
        """RUN -> STOP: no OB runs, outputs are switched off (the output image keeps its values)."""
        was = self.mode
        self.mode = STOP
        self._stack.clear()
        self._switch_outputs_off()
        if was == RUN:
            self._diag("RUN->STOP", f"the CPU switched to STOP ({reason})")

    def power_cycle(self) -> None:
        """Power off and on: retain tags survive, everything else restarts from its start value."""
        self.stop(reason="power off")
        self.start()

    # -- running ------------------------------------------------------------------------------

    @property
    def now(self) -> int:
        """Simulated time in ns."""
        return self.clock.now

    def run(self, duration: str | int) -> None:
        """Run for a duration (``"10s"`` or ns)."""
        self.run_until(self.clock.now + to_ns(duration))

    def scan(self, count: int = 1) -> None:
        """Run ``count`` OB1 executions (scans), interrupts included; the clock stops at the last scan's end."""
        if self.mode == RUN:
            # a scan that run_until() left unfinished (its networks already ran) is finished, not counted
            pending = any(ex.task is self._ob1 for ex in self._stack)
            self._run(_NEVER, self.scan_count + count + pending)

    def next_event_ns(self) -> int:
        """When the CPU next does something (a task start, a network, an output write); far future in STOP."""
        if self.mode != RUN:
            return _NEVER
        t = self._stack[-1].next_time() if self._stack else self._ob1_next
        return max(self.clock.now, min(t, self._next_irq))

    def run_until(self, until_ns: int) -> None:
        """Execute every PLC event up to ``until_ns``: task starts (and their networks) strictly before
        it, and the ends (output writes) of executions finishing at or before it.

        Events at one instant run in this order: the end of an execution that has run its networks
        (its outputs and trace row), then due interrupts by priority, then the start of the next OB1
        scan. So whatever happens at ``until_ns`` itself (an operator's press, an HMI write, a plant's
        new sensor values) is seen by the tasks that start at ``until_ns`` and by no scan before.
        """
        if self._interrupts:
            self._run(until_ns, None)
        else:
            self._run_cyclic(until_ns, None)
        if self.mode != RUN:
            self._refresh_inputs_stopped()
        if self.clock.now < until_ns:
            self.clock.now = until_ns

    def _run(self, until_ns: int, scan_target: int | None) -> None:
        if not self._interrupts:
            self._run_cyclic(until_ns, scan_target)
            return
        stack = self._stack
        ob1 = self._ob1
        while self.mode == RUN:
            if stack:
                ex = stack[-1]
                t_next = ex.next_time()
                prio = ex.task.priority
                preempt = self._next_irq if prio <= 1 else self._preemption_time(prio)
            else:
                ex = None
                t_next = self._ob1_next
                prio = 0
                preempt = self._next_irq
            if preempt < t_next or (preempt == t_next and (ex is None or ex.index < ex.task.n)):
                # an interrupt due at the instant a finished execution ends waits for that end
                irq = self._due_interrupt(t_next, prio)
                start = max(irq.next_due, self.clock.now)  # type: ignore[union-attr]
                if start >= until_ns:
                    return
                self._begin(irq, start)  # type: ignore[arg-type]
                self._run_networks(stack[-1], self._preemption_time(irq.priority))  # type: ignore[union-attr]
                continue
            if t_next > until_ns or (t_next == until_ns and (ex is None or ex.index < ex.task.n)):
                return
            if ex is None:
                self._begin(ob1, t_next)  # type: ignore[arg-type]
                self._run_networks(stack[-1], self._next_irq)
            elif ex.index < ex.task.n:
                self._run_networks(ex, preempt)
            else:
                self._end(ex)
                if scan_target is not None and self.scan_count >= scan_target and ex.task is ob1:
                    return

    def _run_cyclic(self, until_ns: int, scan_target: int | None) -> None:
        """:meth:`_run` for a program without interrupts: the same events, with the calls inlined."""
        task = self._ob1
        ex = task.execution
        stack = self._stack
        clock = self.clock
        n = task.n
        t = self.t
        d = t.__dict__
        inputs = self.inputs
        cfg = self.config
        fixed = 0 if cfg.jitter_ns or cfg.network_cost_ns else max(cfg.cycle_ns, cfg.min_cycle_ns)
        whole = task.merged if task.merged is not None else (task.networks[0] if n == 1 else None)
        aliased_inputs = bool(self._aliased_inputs)
        while self.mode == RUN:
            if not stack:
                t0 = self._ob1_next
                if t0 >= until_ns:
                    return
                if t0 < clock.now:
                    t0 = clock.now
                clock.now = t0
                self._ticks[0] = 0
                if t0 >= self._clock_next:
                    self._latch_clock_memory(t0)
                if aliased_inputs:
                    self._refresh_inputs(task)
                else:
                    d.update(inputs)
                    if self.forces:
                        self._apply_forces()
                duration = fixed or self._cycle_duration(task)
                if duration != ex.duration or not ex.offsets:
                    ex.offsets = task.network_offsets(duration, cfg.network_cost_ns)
                ex.t0, ex.duration, ex.index, ex.shift = t0, duration, 0, 0
                self.scan_start_ns = t0
                stack.append(ex)
                if whole is not None:
                    try:
                        whole(t)
                        ex.index = n
                    except BaseException as exc:  # noqa: BLE001 - sorted out in _after_exception
                        self._after_exception(ex, exc, _NEVER)
                        if self.mode != RUN:  # the fault stopped the CPU: do not run the network again
                            return
            if ex.index < n:
                self._run_networks(ex, _NEVER)
                if ex.index < n or self.mode != RUN:
                    return
            end = ex.t0 + ex.shift + ex.duration
            if end > until_ns:
                return
            stack.pop()
            if end > clock.now:
                clock.now = end
            if self.forces:
                self._apply_forces()
            values = self._out_getter(d)
            if values != self._last_out:
                self._last_out = values
                self.outputs.update(zip(self.output_names, values))
                self.output_version += 1
            self._ob1_next = self.scan_end_ns = end
            self.scan_count += 1
            if self.on_scan_end is not None:
                self.on_scan_end(self)
            if self._first_scan or self._diag_changed:
                self._first_scan = self._diag_changed = False
                self._set_system_bits()
            if scan_target is not None and self.scan_count >= scan_target:
                return

    def _preemption_time(self, priority: int) -> int:
        return min((t.next_due for t in self._interrupts if t.priority > priority), default=_NEVER)

    def _due_interrupt(self, before: int, priority: int) -> _Task | None:
        for task in self._interrupts:  # sorted by priority, highest first
            if task.next_due <= before and task.priority > priority:
                return task
        return None

    def _cycle_duration(self, task: _Task) -> int:
        cfg = self.config
        if task.kind != "cyclic":
            return task.duration_ns or 0
        base = cfg.network_cost_ns * max(1, task.n) if cfg.network_cost_ns else cfg.cycle_ns
        if cfg.jitter_ns:
            base += self._rng.randint(-cfg.jitter_ns, cfg.jitter_ns)
        return max(base, cfg.min_cycle_ns, 1)

    def _begin(self, task: _Task, t0: int) -> None:
        clock = self.clock
        if t0 < clock.now:
            t0 = clock.now
        if self._stack:
            self._stack[-1].paused_at = t0
        if task.kind == "interrupt":
            self._advance_interrupt(task, t0)
        clock.now = t0
        self._ticks[0] = 0
        if t0 >= self._clock_next:
            self._latch_clock_memory(t0)
        self._refresh_inputs(task)
        ex = task.execution
        duration = self._cycle_duration(task)
        if duration != ex.duration or not ex.offsets:
            ex.offsets = task.network_offsets(duration, self.config.network_cost_ns if task.kind == "cyclic" else None)
        ex.t0, ex.duration, ex.index, ex.shift, ex.paused_at = t0, duration, 0, 0, -1
        if task.kind == "cyclic":
            self.scan_start_ns = t0
        self._stack.append(ex)

    def _advance_interrupt(self, task: _Task, start: int) -> None:
        due = task.next_due + task.period_ns
        if due <= start:
            missed = (start - task.next_due) // task.period_ns
            self._diag(
                "cyclic interrupt overrun", f"{task.name} could not run on time; {missed} call(s) lost", task=task.name
            )
            due = task.next_due + (missed + 1) * task.period_ns
        task.next_due = due
        self._next_irq = min(t.next_due for t in self._interrupts)

    def _run_networks(self, ex: _Execution, limit: int) -> None:
        """Run the execution's networks whose boundary comes before ``limit`` (a due interrupt).

        Each sees the execution's start time (plus any time it was pre-empted), so timers count in
        whole scans as the textbook reasons."""
        task = ex.task
        n = task.n
        k = ex.index
        if k >= n:
            return
        base = ex.t0 + ex.shift
        stop = bisect_left(ex.offsets, limit - base, k, n)
        if stop <= k:
            return
        clock = self.clock
        host_now = clock.now  # run_until() may have moved the clock past base: the networks still see base
        clock.now = base
        nets = task.networks
        t = self.t
        try:
            if k == 0 and stop == n and task.merged is not None:
                try:
                    task.merged(t)
                    ex.index = n
                    return
                except JumpTo as jump:
                    k = self._jump_target(task, jump)
                    if k >= stop:
                        ex.index = k
                        return
                except ReturnFromBlock:
                    ex.index = n
                    return
            while True:
                try:
                    for k in range(k, stop):  # noqa: B020 - k must name the failing network
                        nets[k](t)
                    k = stop
                    break
                except JumpTo as jump:
                    k = self._jump_target(task, jump)
                    if k >= stop:
                        break
                except ReturnFromBlock:
                    k = n
                    break
            ex.index = k
        except Exception as exc:  # noqa: BLE001 - a student's error must not crash the host
            ex.index = k
            self._run_failed(ex, exc)
        finally:
            if host_now > clock.now:
                clock.now = host_now

    def _after_exception(self, ex: _Execution, exc: BaseException, until_ns: int) -> None:
        """Handle what a whole-execution call raised: a jump continues network by network, anything else
        is what :meth:`_run_networks` would do with it."""
        task = ex.task
        try:
            raise exc
        except JumpTo as jump:
            try:
                ex.index = self._jump_target(task, jump)
            except (PlcError, CycleWatchdog) as problem:
                self._run_failed(ex, problem)
                return
            self._run_networks(ex, until_ns)
        except ReturnFromBlock:
            ex.index = task.n
        except Exception as problem:  # noqa: BLE001 - a student's error must not crash the host
            self._run_failed(ex, problem)

    def _run_failed(self, ex: _Execution, exc: BaseException) -> None:
        task = ex.task
        k = self._network_of(task, exc, ex.index)
        ex.index = k
        if isinstance(exc, CycleWatchdog):
            self._fault(
                task,
                k,
                "cycle time monitoring exceeded",
                f"the program loops without end; the watchdog ({self.config.watchdog_iterations} loop "
                f"iterations, the stand-in for the 150 ms cycle monitoring) sent the CPU to STOP",
                exc,  # the loop's line, when the loop is in the program (not a backward JMP)
            )
        else:
            self._fault(task, k, "error in the program", _describe(exc), exc)

    def _jump_target(self, task: _Task, jump: JumpTo) -> int:
        target = task.labels.get(jump.label)
        if target is None:
            raise PlcError(
                f"JMP to {jump.label!r}, but no network of {task.name} has that label; "
                f"labels: {', '.join(task.labels) or 'none'}"
            )
        self._ticks[0] += 1
        if self._ticks[0] > self.config.watchdog_iterations:
            raise CycleWatchdog()
        return target

    def _network_of(self, task: _Task, exc: BaseException, default: int) -> int:
        """The network whose code raised ``exc`` (found by line, since merged networks share a frame)."""
        line = _program_line(exc, self.program.filename) if self.program else None
        if line is None:
            return default
        for index, (first, last) in enumerate(task.spans):
            if first <= line <= last:
                return index
        return default

    def _run_atomic(self, task: _Task, t0: int) -> None:
        self._begin(task, t0)
        ex = self._stack[-1]
        self._run_networks(ex, _NEVER)
        if self.mode == RUN:
            ex.duration = 0
            self._end(ex)

    def _end(self, ex: _Execution) -> None:
        stack = self._stack
        stack.pop()
        end = ex.t0 + ex.shift + ex.duration
        if end > self.clock.now:
            self.clock.now = end
        task = ex.task
        self._write_outputs(task)
        if stack:
            below = stack[-1]
            below.shift += end - below.paused_at
        if task.kind == "cyclic":
            self._ob1_next = end
            self.scan_end_ns = end
            self.scan_count += 1
            if self.on_scan_end is not None:
                self.on_scan_end(self)
            if self._first_scan or self._diag_changed:
                self._first_scan = False
                self._diag_changed = False
                self._set_system_bits()
        elif self.on_task_end is not None:
            self.on_task_end(self, task.name, ex.t0, end)

    def _fault(self, task: _Task, k: int, event: str, message: str, exc: BaseException | None) -> None:
        network = task.titles[k] if k < task.n else None
        line = _program_line(exc, self.program.filename) if exc is not None and self.program else None
        where = (
            f"{task.name} network {k + 1}" + (f" ({network})" if network else "") + (f", line {line}" if line else "")
        )
        self._diag(
            event, f"{where}: {message}", task=task.name, network=f"{k + 1} ({network})" if network else None, line=line
        )
        self.stop(reason=f"{event} in {task.name}")

    # -- process images -----------------------------------------------------------------------

    def _refresh_inputs(self, task: _Task) -> None:
        d = self.t.__dict__
        if task.kind == "cyclic":
            inputs = self.inputs
            if self._aliased_inputs:
                for name in self._plain_inputs:
                    d[name] = inputs[name]
                for name in self._aliased_inputs:
                    store(self.t, name, inputs[name])
            else:
                d.update(inputs)
        else:
            for name in task.inputs:
                store(self.t, name, self.inputs[name])
        if self.forces:
            self._apply_forces()

    def _refresh_inputs_stopped(self) -> None:
        for name in self.input_names:
            store(self.t, name, self.inputs[name])

    def _write_outputs(self, task: _Task) -> None:
        if self.forces:
            self._apply_forces()
        d = self.t.__dict__
        if task.kind == "cyclic":
            values = self._out_getter(d)
            if values != self._last_out:
                self._last_out = values
                self.outputs.update(zip(self.output_names, values))
                self.output_version += 1
        elif task.outputs:
            changed = False
            for name in task.outputs:
                if self.outputs[name] != d[name]:
                    self.outputs[name] = d[name]
                    changed = True
            if changed:
                self._last_out = tuple(self.outputs[n] for n in self.output_names)
                self.output_version += 1

    def _switch_outputs_off(self) -> None:
        off = {name: _off(value) for name, value in self.outputs.items()}
        if off != self.outputs:
            self.outputs = off
            self.output_version += 1
        self._last_out = tuple(off[n] for n in self.output_names)

    def _apply_forces(self) -> None:
        for name, value in self.forces.items():
            container, key = self.resolve_path(name)
            store(container, key, value)
            if name in self.outputs:
                self.outputs[name] = self.t.__dict__[name]

    # -- clock and system memory ----------------------------------------------------------------

    def _latch_clock_memory(self, now: int) -> None:
        if self.config.clock_memory_byte is None:
            self._clock_next = _NEVER
            return
        ms = now // 1_000_000
        nxt = _NEVER
        d = self.t.__dict__
        for _, name, half in CLOCK_BITS:
            phase = ms // half
            value = phase % 2 == 1
            if d.get(name) is not value:
                store(self.t, name, value)
            nxt = min(nxt, (phase + 1) * half * 1_000_000)
        self._clock_next = nxt

    def _set_system_bits(self) -> None:
        if self.config.system_memory_byte is None:
            return
        for name, value in (
            ("FirstScan", self._first_scan),
            ("DiagStatusUpdate", self._diag_changed),
            ("AlwaysTRUE", True),
            ("AlwaysFALSE", False),
        ):
            store(self.t, name, value)

    # -- real-time clock ------------------------------------------------------------------------

    def local_time(self) -> tuple[_dt.datetime, int]:
        """The CPU's local date/time now: ``rtc_start`` plus the simulated time; and its nanoseconds."""
        start, nanos = datetime_literal(self.config.rtc_start)
        total = nanos + self.clock.now
        moment = start + _dt.timedelta(microseconds=total // 1000)
        return moment.replace(microsecond=0), (total % 1_000_000_000)

    def local_time_dtl(self) -> dict[str, int]:
        """:meth:`local_time` as DTL members."""
        return dtl_of(*self.local_time())

    # -- host access: watch table, HMI, force ---------------------------------------------------

    def resolve_path(self, path: str) -> tuple[Any, Any]:
        """Find where ``"NAME"``, ``"DB.member"``, ``"DB.arr[2].x"`` or ``"%MW10"`` lives: (container, key)."""
        if not isinstance(path, str) or not path:
            raise UnknownTagError(f"a tag is named by a string such as 'LED' or 'DATA.D1_OBS', not {path!r}")
        text = path.strip()
        if text.startswith("%"):
            key = str(parse_address(text))
            if key in self.t.__dict__:
                return self.t, key
            entry = self.table.by_address(parse_address(text))
            if entry is not None:
                return self.t, entry.name
            raise UnknownTagError(f"no tag at {key}; declare it (Tag({key!r}, ...)) or use it in the program")
        parts = _split_path(text)
        container: Any = self.t
        for i, part in enumerate(parts[:-1]):
            container = _step(container, part, ".".join(str(p) for p in parts[: i + 1]))
        last = parts[-1]
        if isinstance(container, PlcArray):
            if not isinstance(last, int):
                raise UnknownTagError(f"{path}: an array needs an index, e.g. {text}[0]")
            container._index(last)
            return container, last
        if isinstance(container, (IecTimer, IecCounter, EdgeTrigger)):
            if not isinstance(last, str) or last.startswith("_") or not hasattr(container, last):
                raise UnknownTagError(f"{path}: an instance of {type(container).__name__} has no member {last!r}")
            return container, last
        if not isinstance(container, PlcStruct):
            raise UnknownTagError(f"{path}: {parts[-2]} has no members")
        if last not in container._type.members:
            where = "no tag" if container is self.t else f"{container._path} has no member"
            raise UnknownTagError(f"{where} {last!r}{did_you_mean(str(last), container._type.members)}")
        return container, last

    def _resolve_value(self, path: str) -> Any:
        container, key = self.resolve_path(path)
        if isinstance(container, (IecTimer, IecCounter, EdgeTrigger)):
            return getattr(container, key)
        return container[key]

    def read(self, name: str) -> Any:
        """Read a tag, DB member, instance member (``"TON_1.ET"``, ``"C1.CV"``) or address as a watch table
        shows it (never refreshes a timer)."""
        text = name.strip()
        if text.startswith("%"):
            return self.peek(text)
        head, _, member = text.rpartition(".")
        owner = self._resolve_value(head) if head and "[" not in member else None
        if isinstance(owner, (IecTimer, IecCounter, EdgeTrigger)):  # "TON_1.ET", "C1.CV": instance members
            if isinstance(owner, IecTimer) and member in ("Q", "ET"):
                return owner.peek()[member == "ET"]
            if member.startswith("_") or not hasattr(owner, member):
                raise UnknownTagError(f"{head} has no member {member!r}")
            return getattr(owner, member)
        return self._resolve_value(text)

    def peek(self, address: str | Address) -> Any:
        """Read an absolute address from memory, composing it from every tag that overlaps it."""
        addr = parse_address(address) if isinstance(address, str) else address
        key = (addr.area, addr.db)
        memory = self.memories.get(key)
        if memory is None:
            raise UnknownTagError(f"{addr}: no such memory area (is the DB non-optimized?)")
        for container, name, caddr, dtype in self._cells:
            if caddr.area == addr.area and caddr.db == addr.db and caddr.byte < addr.end and addr.byte < caddr.end:
                memory.write(caddr, dtype, container.__dict__[name])
        return memory.read(addr, addr.default_type())

    def write(self, name: str, value: Any) -> None:
        """Modify a tag once, as a watch table or an HMI does; the program may overwrite it next scan."""
        container, key = self.resolve_path(name)
        if isinstance(container, PlcArray):
            container[key] = value
        elif isinstance(container, (IecTimer, IecCounter)):
            _fb_store(container, key, value)
        else:
            store(container, key, value)
        if key in self.inputs and container is self.t:
            self.inputs[key] = self.t.__dict__[key]
            self._sync_terminals(key)

    def set_input(self, name: str, value: Any) -> None:
        """Drive a physical input terminal (a sensor or a button); the program sees it at its next task start."""
        if name not in self.inputs:
            raise UnknownTagError(
                f"no input {name!r}{did_you_mean(name, self.inputs)}; inputs: {', '.join(self.inputs) or 'none'}"
            )
        member = self.table[name].member
        self.inputs[name] = member.type.coerce(value, name)  # type: ignore[union-attr]
        self._sync_terminals(name)

    def _sync_terminals(self, name: str) -> None:
        """After input ``name`` changed, give every input tag that overlaps it the same terminals."""
        cell = self._input_cells.get(name)
        if cell is not None:
            self._terminals.write(cell.address, cell.dtype, self.inputs[name])
            for other in cell.others:
                if other.key in self._input_cells:
                    self.inputs[other.key] = self._terminals.read(other.address, other.dtype)

    def force(self, name: str, value: Any) -> None:
        """Force a tag: its value is re-applied at every image update, whatever the program writes."""
        container, key = self.resolve_path(name)
        member_type = container._type.members[key].type if isinstance(container, PlcStruct) else None
        if isinstance(member_type, ElementaryType):
            value = member_type.coerce(value, name)
        self.forces[name] = value
        self._diag("force", f"{name} forced to {value!r}")

    def unforce(self, name: str | None = None) -> None:
        """Remove one force (or all): the tag keeps the forced value until something writes it."""
        names = list(self.forces) if name is None else [name]
        for n in names:
            if n not in self.forces:
                raise UnknownTagError(f"{n!r} is not forced; forced: {', '.join(self.forces) or 'nothing'}")
            del self.forces[n]

    # -- diagnostics ----------------------------------------------------------------------------

    def _diag(
        self, event: str, message: str, task: str | None = None, network: str | None = None, line: int | None = None
    ) -> None:
        self.diagnostics.append(DiagnosticEntry(self.clock.now, event, message, task, network, line))
        self._diag_changed = True

    @property
    def error(self) -> DiagnosticEntry | None:
        """The entry that last stopped the CPU, if it is in STOP because of an error."""
        if self.mode == RUN:
            return None
        for entry in reversed(self.diagnostics):
            if entry.event in ("error in the program", "cycle time monitoring exceeded"):
                return entry
            if entry.event == "STOP->RUN":
                return None
        return None

    def __repr__(self) -> str:
        prog = self.program.filename if self.program else "no program"
        return f"<CPU {self.config.family} {self.mode} t={format_ns(self.clock.now)} scans={self.scan_count} {prog}>"


_NEVER = 1 << 62


def _off(value: Any) -> Any:
    if isinstance(value, bool):
        return False
    if isinstance(value, float):
        return 0.0
    if isinstance(value, int):
        return 0
    return value


def _getter(names: list[str]) -> Callable[[dict[str, Any]], tuple[Any, ...]]:
    if not names:
        return lambda d: ()
    if len(names) == 1:
        only = operator.itemgetter(names[0])
        return lambda d: (only(d),)
    return operator.itemgetter(*names)


def _describe(exc: BaseException) -> str:
    text = str(exc)
    name = type(exc).__name__
    if isinstance(exc, PlcError):
        return text
    return f"{name}: {text}" if text else name


def _program_line(exc: BaseException, filename: str) -> int | None:
    for frame in reversed(traceback.extract_tb(exc.__traceback__)):
        if frame.filename == filename:
            return frame.lineno
    return None


def _store_any(container: Any, key: str, value: Any) -> None:
    if isinstance(container, PlcStruct):
        store(container, key, value)
        return
    raise PlcTypeError(
        f"cannot store into {type(container).__name__}.{key}; a program stores only into tags "
        f"(t.NAME) and data-block members (t.DB.member)"
    )


def _fb_store(instance: Any, key: str, value: Any) -> None:
    if isinstance(instance, IecTimer) and key == "PT":
        instance.PT = preset_ms(value, f"{instance._path}.PT")
    elif isinstance(instance, IecCounter) and key in FB_WRITABLE["IEC_COUNTER"]:
        setattr(instance, key, instance._type.coerce(value, f"{instance._path}.{key}"))
    else:
        raise PlcTypeError(f"{key} of {instance!r} cannot be written by the program")


def _split_path(text: str) -> list[Any]:
    parts: list[Any] = []
    for chunk in text.split("."):
        name, _, rest = chunk.partition("[")
        if name:
            parts.append(name)
        while rest:
            index, _, rest = rest.partition("]")
            try:
                parts.append(int(index))
            except ValueError:
                raise UnknownTagError(f"{text!r}: array index {index!r} must be an integer") from None
            rest = rest.lstrip("[")
    return parts


def _step(container: Any, part: Any, shown: str) -> Any:
    if isinstance(part, int):
        if not isinstance(container, PlcArray):
            raise UnknownTagError(f"{shown} is not an array")
        return container[part]
    if isinstance(container, PlcStruct):
        if part not in container.__dict__:
            where = "no tag" if container._path == "t" else f"{container._path} has no member"
            raise UnknownTagError(f"{where} {part!r}{did_you_mean(part, container._type.members)}")
        return container.__dict__[part]
    raise UnknownTagError(f"{shown}: {type(container).__name__} has no member {part!r}")


def _address_strings(program: Program) -> list[str]:
    import ast

    found = []
    for node in ast.walk(program.tree):
        if isinstance(node, ast.Constant) and isinstance(node.value, str) and node.value.strip().startswith("%"):
            try:
                parse_address(node.value)
            except PlcError:
                continue
            found.append(node.value)
    return found


def _period_given(program: Program, name: str) -> bool:
    import ast

    for stmt in program.tree.body:
        if isinstance(stmt, ast.Assign) and any(isinstance(t, ast.Name) and t.id == name for t in stmt.targets):
            call = stmt.value
            return isinstance(call, ast.Call) and any(k.arg == "period" for k in call.keywords)
    return False


__all__ = ["CPU", "CPUConfig", "DiagnosticEntry", "RUN", "STOP", "CLOCK_BITS", "SYSTEM_BITS", "Bool", "Int"]
