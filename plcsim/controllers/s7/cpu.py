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
import pkgutil
import random
import sys
from collections import deque
from collections.abc import Mapping
from dataclasses import replace
from typing import Any

from plcsim.controllers.loaded import LinkTarget, LoadedProgram, LoadedTask, RuntimeHooks, SourceProgram, TaskSpec
from plcsim.controllers.protocol import RUN, STOP, DiagnosticEntry
from plcsim.controllers.s7.access import HostAccess, store_instance_member, store_into
from plcsim.controllers.s7.config import CLOCK_BITS, SYSTEM_BITS, CPUConfig
from plcsim.controllers.s7.execution import (
    NEVER,
    CycleWatchdog,
    Execution,
    RunningTask,
    TaskRunner,
    switched_off,
    tuple_getter,
)
from plcsim.controllers.s7.fused import FusedScan, InputsIn, ScanRow, fused_scan
from plcsim.controllers.s7.instructions import bind_instructions, block_of
from plcsim.controllers.s7.instructions.timers import IecTimer
from plcsim.controllers.s7.profile import DEFAULT_INTERRUPT_PERIOD, PROFILE
from plcsim.core.clock import Clock
from plcsim.core.errors import ConfigurationError, PlcTypeError
from plcsim.core.literals import datetime_literal, format_ns, to_ns
from plcsim.core.observers import Subscribers, assigned_hook
from plcsim.tags.aliasing import non_optimized_offsets
from plcsim.tags.memory import Address, ByteMemory, parse_address
from plcsim.tags.runtime import build_runtime
from plcsim.tags.table import Tag, TagTable
from plcsim.tags.types import Bool, Int
from plcsim.tags.values import PlcStruct, reset_to_start


class CPU(TaskRunner, HostAccess):
    """A simulated S7-1200 CPU running one program on the one clock.

    Args:
        tags: the tag table (an exercise's I/O table); a mapping ``name -> Tag(...)`` is accepted.
        program: a program a front end read (:func:`plcsim.frontends.read_program`), program text in the
            profile's default language (the Python subset), or None (load later).
        config: a :class:`CPUConfig`; keyword ``options`` build one instead.
        start: switch to RUN after loading the program (as after a download and a mode switch).

    Physical I/O: write sensor values into :attr:`inputs` (or :meth:`set_input`); read what the output
    modules drive from :attr:`outputs` (all off in STOP).
    """

    system_tags = frozenset(name for _, name, _ in CLOCK_BITS) | frozenset(name for _, name in SYSTEM_BITS)
    """The clock and system memory bits (``Clock_1Hz``, ``FirstScan`` ...): traced only where a program uses them."""

    def __init__(
        self,
        tags: TagTable | Mapping[str, Any] | None = None,
        program: SourceProgram | str | None = None,
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
        self.scan_end = Subscribers()
        """Called as ``(cpu)`` when an OB1 scan has written its outputs."""
        self.task_end = Subscribers()
        """Called as ``(cpu, task name, start ns, end ns)`` when another task's execution has ended."""
        self.cut = Subscribers()
        """Called as ``(cpu, task name, start ns)`` for each execution a power cut interrupts."""
        self.task_numbers: dict[str, int] = {}
        """Task name -> its number in the trace's task column (from the loaded program's tasks)."""
        self.scan_task_number = 1
        """The cyclic task's number (the rows of OB1 scans)."""
        self.scan_count = 0
        self.scan_start_ns = 0
        self.scan_end_ns = 0
        self.output_version = 0
        self.program: SourceProgram | None = None
        self.loaded: LoadedProgram | None = None
        self.compiled: Any = None
        """The Python front end's compiled form (its analysis feeds the static checks); None for another."""
        self.warnings: list[str] = []
        self.downloads = 0
        """How many downloads changed the program while it ran (:meth:`download`)."""
        self._rng = random.Random(self.config.seed)
        self._stack: list[Execution] = []
        self._ob1: RunningTask | None = None
        self._cyclic_plan: tuple[int, Any, bool] = (0, None, False)
        self._cyclic: Any = None  # the generator of TaskRunner._cyclic_loop (made at each download)
        self._fused: FusedScan | None = None  # one whole OB1 scan in one call (made at each download)
        self._interrupts: list[RunningTask] = []
        self._next_irq = NEVER
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

    on_scan_end = assigned_hook("scan_end", "One :attr:`scan_end` subscriber, set by assignment.")
    on_task_end = assigned_hook("task_end", "One :attr:`task_end` subscriber, set by assignment.")
    on_cut = assigned_hook("cut", "One :attr:`cut` subscriber, set by assignment.")

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
        # interned as the keys of t: the image copies and the output getter find them by identity
        self.input_names = [sys.intern(e.name) for e in table if e.address is not None and e.address.area == "I"]
        self.output_names = [sys.intern(e.name) for e in table if e.address is not None and e.address.area == "Q"]
        self.inputs = {name: self.inputs.get(name, self.t.__dict__[name]) for name in self.input_names}
        self.outputs = {name: switched_off(self.t.__dict__[name]) for name in self.output_names}
        # each input as the plant delivered it at its last refresh (what the trace records)
        self.image_in: dict[str, Any] = dict(self.inputs)
        aliased = {c.key for c in self.aliases if c.container is self.t}
        self._aliased_inputs = [n for n in self.input_names if n in aliased]
        self._plain_inputs = [n for n in self.input_names if n not in aliased]
        # the input terminals of overlapping input tags (%IW64 and %I65.0) are one memory too
        self._input_cells = {c.key: c for c in self.aliases if c.container is self.t and c.key in self.inputs}
        self._terminals = ByteMemory("I", self.config.memory.inputs)
        for name, cell in self._input_cells.items():
            self._terminals.write(cell.address, cell.dtype, self.inputs[name])
        self._out_getter = tuple_getter(self.output_names)
        self._last_out: tuple[Any, ...] = self._out_getter(self.outputs)
        if self.config.retentive_markers:
            self._retentive_m = bytes(self.memories[("M", None)].data[: self.config.retentive_markers])

    # -- loading ------------------------------------------------------------------------------

    def load(self, program: SourceProgram | str) -> None:
        """Download a program (the CPU goes to STOP; call :meth:`start` for RUN).

        ``program`` is what a front end read (:func:`plcsim.frontends.read_program`), or Python subset text."""
        if isinstance(program, str):
            program = pkgutil.resolve_name(PROFILE.source_reader)(program)
        was_running = self.mode == RUN
        self.stop(reason="download")
        table = program.declare_into(self.base_table)
        self._load_table(table, program.absolute_addresses())
        aliased = frozenset(c.key if c.container is self.t else f"{c.container._path}.{c.key}" for c in self.aliases)
        loaded = program.link(LinkTarget(self.table, aliased, self.config, bind_instructions(self), self._hooks()))
        self.program, self.loaded, self.compiled, self.warnings = program, loaded, loaded.compiled, loaded.warnings
        for path in loaded.inert_timers:
            timer = self._resolve_value(path.split(".", 1)[1] if "." in path else path)
            if isinstance(timer, IecTimer):
                timer.make_inert()
        _check_task_numbers(loaded)
        tasks = [self._running_task(task) for task in loaded.tasks]
        self._ob1 = next((t for t in tasks if t.kind == "cyclic"), None) or RunningTask(
            TaskSpec("OB1", "cyclic", [], number=1), []
        )
        self._ob1.inputs, self._ob1.outputs = list(self.input_names), list(self.output_names)
        self._interrupts = sorted((t for t in tasks if t.kind == "interrupt"), key=lambda t: -t.priority)
        self._startup = [t for t in tasks if t.kind == "startup"]
        self.task_numbers = {t.name: t.number for t in [self._ob1, *tasks]}
        self.scan_task_number = self._ob1.number
        self._plan_cyclic()
        names = ", ".join(t.spec.name for t in loaded.tasks) or "no OBs"
        self._diag("download", f"program {loaded.filename} loaded: {names}")
        if was_running:
            self.start()

    def download(self, text: str, filename: str = "<downloaded program>") -> None:
        """Download a changed program as TIA Portal does into a running CPU: STOP, load, RUN (if it ran).

        Every tag, DB member and instance that keeps its name and type keeps its value, and then STOP -> RUN
        does what it always does: non-retain tags take their start values, retain ones (counters, retain
        tags) keep theirs. The inputs keep their terminals. A program that does not compile is refused
        before the CPU stops (the error names the file and the line)."""
        program = pkgutil.resolve_name(PROFILE.source_reader)(text, filename)
        CPU(self.base_table, program, replace(self.config), start=False, clock=Clock(self.clock.now))  # a dry run
        was_running = self.mode == RUN
        if was_running:
            self.stop(reason="download")
        old, inputs = self.t, self.inputs
        self.load(program)
        _carry_values(old, self.t)
        inputs.clear()
        inputs.update(self.inputs)
        self.inputs = inputs  # the same dict: whoever drives the terminals (the wiring) keeps writing into it
        self._plan_cyclic()  # the scan loop reads the inputs from there
        self.downloads += 1
        if was_running:
            self.start()

    def _running_task(self, loaded: LoadedTask) -> RunningTask:
        """A loaded task on this CPU: its timing (the configured period if the program gives none) and
        its process-image partition (OB1 all inputs and outputs; an interrupt the ones it uses)."""
        spec = loaded.spec
        task = RunningTask(spec, [n.run for n in loaded.networks], loaded.whole, [n.span for n in loaded.networks])
        if spec.kind == "cyclic":
            task.inputs, task.outputs = list(self.input_names), list(self.output_names)
        else:
            task.inputs = [n for n in self.input_names if n in loaded.tags_used]
            task.outputs = [n for n in self.output_names if n in loaded.tags_used]
        if spec.kind == "interrupt" and spec.period_ns is None:  # the hardware configuration's, or the default
            task.period_ns = to_ns(self.config.periods.get(spec.name, DEFAULT_INTERRUPT_PERIOD), f"{spec.name} period")
        if task.duration_ns is None:
            task.duration_ns = self.config.interrupt_duration_ns if spec.kind == "interrupt" else 0
        return task

    def _hooks(self) -> RuntimeHooks:
        """The runtime's hooks bound to this CPU, for the code a front end generates: the watchdog tick and
        the store guards."""
        ticks = self._ticks
        budget = self.config.watchdog_iterations

        def tick() -> None:
            ticks[0] += 1
            if ticks[0] > budget:
                raise CycleWatchdog()

        def tags_of(tags: Any) -> dict[str, Any]:
            if tags is not self.t:
                raise PlcTypeError(
                    f"a network was called with {type(tags).__name__} instead of the tags; call a network "
                    f"(or a function that stores into t.NAME) with t"
                )
            return tags.__dict__

        return RuntimeHooks(tick, tags_of, store_into, store_instance_member)

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
        self._next_irq = min((t.next_due for t in self._interrupts), default=NEVER)
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
        """Power off and on: retain tags survive, everything else restarts from its start value.

        An execution the power cut interrupts keeps what its networks already did (a retentive tag it
        changed keeps the change, as on a real S7-1200); :attr:`cut` reports it, so that the trace
        has a row for it before the restart."""
        cut = [(ex.task.name, ex.t0) for ex in reversed(self._stack)]
        self.stop(reason="power off")
        if self.cut.call is not None:
            for task, t0 in cut:
                self.cut.call(self, task, t0)
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
        fused = self._fused
        if count == 1 and fused is not None and fused(NEVER):
            return  # the common case: one whole scan in one call
        if self.mode != RUN:
            return
        target = self.scan_count + count
        while fused is not None and fused(NEVER):  # whole scans, one call each
            if self.mode != RUN or self.scan_count >= target:
                return
            fused = self._fused  # a subscriber may have downloaded another program
        # a scan that run_until() left unfinished (its networks already ran) is finished, not counted
        pending = bool(self._stack) and any(ex.task is self._ob1 for ex in self._stack)
        self._run(NEVER, target + pending)

    def fused_scan(
        self, before: InputsIn | None = None, after: ScanRow | None = None, replaces: Any = None, fills: bool = False
    ) -> FusedScan | None:
        """One whole OB1 scan per call (``scan(until_ns)``, whether it ran) with a host's work at its two ends:
        ``before(inputs, t0)`` once the scan is sure to run, before it reads the inputs; ``after(t0, end)`` at
        its end in place of the :attr:`scan_end` subscriber ``replaces``; with ``fills``, only a scan that ends
        at ``until_ns``. None where this program's scans cannot be fused
        (:func:`plcsim.controllers.s7.fused.fused_scan`); build it again after a download."""
        return fused_scan(self, before, after, replaces, fills)

    @property
    def fixed_cycle_ns(self) -> int:
        """How long every OB1 scan lasts, or 0 when it varies (a jitter, a cost per network)."""
        return self._cyclic_plan[0]

    def next_event_ns(self) -> int:
        """When the CPU next does something (a task start, a network, an output write); far future in STOP."""
        if self.mode != RUN:
            return NEVER
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
        fused = self._fused
        while fused is not None and fused(until_ns):  # whole scans, one call each (none in STOP)
            fused = self._fused  # a subscriber may have downloaded another program
        if self.mode == RUN and (self._stack or self._ob1_next < until_ns or self._next_irq < until_ns):
            if self._interrupts:  # TaskRunner._run without a call of its own: this is every physics step's
                self._run_preemptive(until_ns, None)
            else:
                self._run_cyclic(until_ns, None)
        if self.mode != RUN:
            self._refresh_inputs_stopped()
        if self.clock.now < until_ns:
            self.clock.now = until_ns

    # -- real-time clock ------------------------------------------------------------------------

    def local_time(self) -> tuple[_dt.datetime, int]:
        """The CPU's local date/time now: ``rtc_start`` plus the simulated time; and its nanoseconds."""
        start, nanos = datetime_literal(self.config.rtc_start)
        total = nanos + self.clock.now
        moment = start + _dt.timedelta(microseconds=total // 1000)
        return moment.replace(microsecond=0), (total % 1_000_000_000)

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


def _check_task_numbers(loaded: LoadedProgram) -> None:
    """Each task has its own trace number, and none is 0 (the rows in STOP): else a front end's bug."""
    seen: dict[int, str] = {}
    for task in loaded.tasks:
        number, name = task.spec.number, task.spec.name
        if number <= 0 or number in seen:
            why = f"the same number {number} as {seen[number]}" if number in seen else f"the number {number}"
            raise ConfigurationError(
                f"{loaded.filename}: the front end gave task {name} {why}; each task needs its own number > 0 "
                f"for the trace's task column"
            )
        seen[number] = name


__all__ = ["CPU", "CPUConfig", "DiagnosticEntry", "RUN", "STOP", "CLOCK_BITS", "SYSTEM_BITS", "Bool", "Int"]


def _carry_values(old: PlcStruct, new: PlcStruct) -> None:
    """Copy into ``new`` every value of ``old`` whose name and type are the same (instances by object)."""
    for name, member in new._type.members.items():
        before = old._type.members.get(name)
        if before is None or before.type != member.type or name not in old.__dict__:
            continue
        value, fresh = old.__dict__[name], new.__dict__.get(name)
        if isinstance(value, PlcStruct) and isinstance(fresh, PlcStruct):
            _carry_values(value, fresh)
        elif type(value) is type(fresh) and (isinstance(value, bool | int | float | str) or block_of(value)):
            new.__dict__[name] = value
