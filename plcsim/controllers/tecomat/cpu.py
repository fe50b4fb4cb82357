"""The Tecomat controller the simulation drives: the program cycle, its processes, S, restarts.

One cycle (manual §2, §4.1.1, Fig. 2 and 5), on the one integer clock:

1. **turnaround at t0**: the system updates S (S2 state flags, S5..S12 real-time clock, S13 clock bits,
   S14..S19 unit counters), samples the inputs into X (and the direct inputs U), clears stack A
   (all eight with ``clear_all_stacks``) and activates it, and plans the processes;
2. **the processes**, in the order we read Fig. 5: P63/P62 in the first cycle after a cold/warm restart,
   P41..P48 whose event was raised and enabled, P0, the one of P1..P4 whose phase it is, the due ones of
   P5..P9, P10..P40 whose mask bit is set, P64; EOC ends the cycle early (P64 still runs unless
   ``final_after_eoc`` is off); P50..P57 run when BP calls them, P60 holds subroutines;
3. **end at t0 + cycle**: Y goes to the outputs, the trace row is written, the next cycle starts.

Direct inputs U read the terminals as the wiring delivers them; all instructions of a cycle run at its
start instant, so U differs from X only where the program wrote X.

The controller offers what :class:`plcsim.sim.simulation.Simulation` needs from a CPU (see
:mod:`plcsim.controllers.protocol`): inputs and outputs by the program's symbol names (``#def START x0.0``),
``run_until``, the scan hooks the recorder subscribes to, and a tag table so that the wiring and the
trace speak of ``START`` and ``MOTOR`` rather than ``X0.0``.

>>> cpu = TecomatCPU("#def START x0.0\\n#def STOP x0.1\\n#def MOTOR y0.0\\nLD START\\nOR MOTOR\\nANC STOP\\nWR MOTOR")
>>> cpu.set_input("START", True); cpu.scan(); cpu.set_input("START", False); cpu.scan()
>>> cpu.outputs["MOTOR"]
True
"""

from __future__ import annotations

import datetime as _dt
from collections import deque
from collections.abc import Mapping
from operator import itemgetter
from pathlib import Path
from struct import pack_into
from typing import Any

from plcsim.controllers.loaded import LoadedProgram, ProgramFacts
from plcsim.controllers.protocol import RUN, STOP, DiagnosticEntry
from plcsim.controllers.tecomat import verbs
from plcsim.controllers.tecomat.analysis import IlAnalysis, IlCompiled
from plcsim.controllers.tecomat.assembler import assemble
from plcsim.controllers.tecomat.assembly import Assembly
from plcsim.controllers.tecomat.fused import Cycle
from plcsim.controllers.tecomat.linker import link
from plcsim.controllers.tecomat.machine import END_CYCLE, ZEROS, Machine, TecomatRuntimeError
from plcsim.controllers.tecomat.memory import Operand, OperandError, Scratchpad, parse_address, read, write
from plcsim.controllers.tecomat.settings import TecomatConfig
from plcsim.controllers.tecomat.symbols import copies, function, overlapping, publisher, reader, sampler, snapshot
from plcsim.core.clock import NEVER, Clock
from plcsim.core.errors import ConfigurationError, UnknownTagError, did_you_mean
from plcsim.core.literals import to_ns
from plcsim.core.observers import Subscribers, assigned_hook
from plcsim.tags.table import Tag, TagTable
from plcsim.tags.types import Bool, Byte, DWord, Word

CLOCK_PERIODS_NS = tuple(
    to_ns(p) for p in ("100ms", "500ms", "1s", "10s", "1min", "10min", "1h", "24h")
)  # S13.0 .. S13.7
HALF_PERIODS_NS = tuple(p // 2 for p in CLOCK_PERIODS_NS)
S2_RUNNING = 1 | 1 << 2 | 1 << 5
"""S2 in RUN: SP (external start), RUN, ON (outputs active); MS, MEZ and the first-cycle flags clear."""
TASK = "cycle"
"""The trace's name of a program cycle (all its processes together make one row)."""


class _Symbols:
    """The symbols' values after the last cycle, as attributes (what the trace reads)."""


class TecomatCPU:
    """A simulated Tecomat NS950 running one ``.il`` program.

    Args:
        program: source text, an :class:`Assembly`, or None (:meth:`load` later).
        config: a :class:`TecomatConfig`; keyword ``options`` build one instead.
        symbols: extra names bound to addresses (``{"TLACIDLO": "X0.0"}``), e.g. an exercise's I/O names.
        start: cold-start into RUN after loading.
        clock: the clock to run on (a simulation shares one with the plant); a new one at 0 by default.
        filename: the program's name in error messages and diagnostics.
        **options: fields of :class:`TecomatConfig` (``cycle="10ms"``), when no ``config`` is given.

    Attributes:
        mode: ``"RUN"`` or ``"STOP"``.
        inputs: each input symbol's level as last driven (:meth:`set_input`, the wiring).
        outputs: each output symbol's value as the last cycle's end wrote Y (all off in STOP).
        scan_count: the cycles run so far.
        warnings: what was noticed about the program and its options (``#include`` ignored, an I/O name
            spelt like an address, an option the Tecomat does not have ...).
        diagnostics: the diagnostic buffer, newest last: downloads, mode changes, errors (1000 kept).
        symbols: the names of X, Y and R the program declares (and ``symbols``), as operands.
        program: the loaded :class:`Assembly`.
        machine: the state the program runs on: the scratchpad ``machine.pad``, the stacks, the linked code.
    """

    family = "Tecomat NS950"
    system_tags: frozenset[str] = frozenset()
    """The Tecomat's system registers (S) are no tags: nothing to leave out of the default trace."""
    VERBS = verbs.VERBS
    """The scenario verbs this controller brings (:mod:`plcsim.controllers.tecomat.verbs`)."""
    interrupt_sources = verbs.SOURCES

    def __init__(
        self,
        program: Assembly | str | None = None,
        config: TecomatConfig | None = None,
        *,
        symbols: Mapping[str, str] | None = None,
        start: bool = True,
        clock: Clock | None = None,
        filename: str = "<il>",
        **options: Any,
    ):
        if config is not None and options:
            raise ConfigurationError("give either config=TecomatConfig(...) or keyword options, not both")
        self.config = config or TecomatConfig(**options)
        self.clock = clock or Clock()
        self.extra_symbols = dict(symbols or {})
        self.mode = STOP
        self.diagnostics: deque[DiagnosticEntry] = deque(maxlen=1000)
        self.scan_end = Subscribers()
        self.task_end = Subscribers()
        self.cut = Subscribers()
        self.task_numbers = {TASK: 1}
        self.scan_task_number = 1
        self.scan_count = 0
        self.scan_start_ns = self.scan_end_ns = 0
        self.output_version = 0
        self.inputs: dict[str, Any] = {}
        self.outputs: dict[str, Any] = {}
        self._y_keys: list[int] = []
        self._image_in: dict[str, Any] = {}
        self._sampled: tuple[Any, ...] | None = None
        """The input levels the last turnaround sampled, not yet in :attr:`image_in` (brought there when read)."""
        self.input_names: list[str] = []
        self.output_names: list[str] = []
        self.symbols: dict[str, Operand] = {}
        self._t = _Symbols()
        self._copies: tuple[bytearray, ...] | None = None
        self.table = TagTable()
        self.program: Assembly | None = None
        self.loaded: LoadedProgram | None = None
        self.compiled: IlCompiled | None = None
        """What the program uses, for an exercise's static checks (``program_uses_no("SET")``)."""
        self.machine: Machine | None = None
        self._head: Any = None
        self._p0 = 0
        self.warnings: list[str] = []
        self.events_raised: set[int] = set()
        self._pending: int | None = None
        self._next_start = 0
        self._restart: str | None = None
        self._started = False
        self._set_rtc_base(_parse_rtc(self.config.rtc_start))
        if program is not None:
            self.load(program, filename)
            if start:
                self.start()

    on_scan_end = assigned_hook("scan_end", "One :attr:`scan_end` subscriber, set by assignment.")

    @property
    def image_in(self) -> dict[str, Any]:
        """Each input as the last sample of the process image read it (what the trace records)."""
        sampled = self._sampled
        if sampled is not None:
            self._sampled = None
            self._image_in.update(zip(self.input_names, sampled, strict=True))
        return self._image_in

    @property
    def t(self) -> _Symbols:
        """The symbols' values at the last cycle's end, as attributes (what the trace and the checks read).

        A cycle's end copies the registers they live in, and decodes them only if a :attr:`scan_end`
        subscriber (the recorder) is there to read them; else they are decoded here, when read."""
        copies = self._copies
        if copies is not None:
            self._copies = None
            self._decode_traced(self._t.__dict__, *copies)
        return self._t

    # -- loading --------------------------------------------------------------------------------

    def load(self, program: Assembly | str, filename: str = "<il>") -> None:
        """Download a program (STOP; :meth:`start` for RUN)."""
        asm = program if isinstance(program, Assembly) else assemble(program, filename, r_size=self.config.r_size)
        self.stop(reason="download")
        self.program, self.warnings = asm, list(asm.warnings)
        self._started = False
        self.machine = Machine(asm, self.config)
        self.compiled = IlCompiled(IlAnalysis.of(asm))
        self.terminals = Scratchpad({"X": bytearray(self.config.x_size)})
        """The input terminals as the plant drives them; the turnaround samples them into X and U."""
        self.symbols = self._symbol_table(asm)
        self._build_table()
        cycle = self._cycle()
        self.machine.code = link(self.machine, cycle=cycle)
        self._head, self._p0 = cycle.head, asm.processes.get(0, 0)
        """The whole cycle of a program of P0 alone as one call ``head(t0)``, or None; used while it is still
        P0's code (the online view links the machine again, one closure per line, and then runs that)."""
        ops = {i.mnemonic for i in asm.code} - {"E"}
        self.loaded = LoadedProgram(
            asm.filename,
            [],
            ProgramFacts(frozenset(self.input_names), frozenset(self.output_names), frozenset(ops)),
            warnings=self.warnings,
        )
        self._diag("download", f"program {asm.filename} loaded: processes {', '.join(f'P{n}' for n in asm.processes)}")

    def _symbol_table(self, asm: Assembly) -> dict[str, Operand]:
        symbols = {s.name: s.operand for s in asm.symbols.values() if s.operand is not None and s.operand.area in "XYR"}
        for name, text in self.extra_symbols.items():
            try:
                symbols[name] = parse_address(text)
            except OperandError as exc:
                raise ConfigurationError(f"symbol {name}: {exc}") from None
        return symbols

    def _build_table(self) -> None:
        table = TagTable()
        self.input_names, self.output_names = [], []
        types = {"bit": Bool, "byte": Byte, "word": Word, "long": DWord}
        for name, op in self.symbols.items():
            s7 = {
                "bit": f"{op.index}.{op.bit}",
                "byte": f"B{op.index}",
                "word": f"W{op.index}",
                "long": f"D{op.index}",
            }[op.width]
            if op.area == "X":
                table.add(name, Tag(f"%I{s7}", types[op.width]), source=self.program.filename)
                self.input_names.append(name)
            elif op.area == "Y":
                table.add(name, Tag(f"%Q{s7}", types[op.width]), source=self.program.filename)
                self.output_names.append(name)
            else:
                table.add(name, types[op.width], source=self.program.filename)
        self.table = table
        self.inputs = {n: self.inputs.get(n, self._off(n)) for n in self.input_names}
        self._image_in, self._sampled = dict(self.inputs), None
        self.outputs = {n: self._off(n) for n in self.output_names}
        self._copies = None
        self._t.__dict__.clear()
        self._t.__dict__.update({n: self._off(n) for n in self.symbols})
        pad = self.machine.pad  # type: ignore[union-attr]
        traced = [n for n in self.symbols if n not in self.inputs]
        self._take_traced, decode = snapshot(pad, [self.symbols[n] for n in traced])
        self._decode_traced = decode(traced)
        self._copied = copies([self.symbols[n] for n in traced])
        """``_take_traced()`` as an expression (the generated cycle copies the registers itself)."""
        lines, names, units = publisher([(n, self.symbols[n]) for n in self.output_names])
        self._publish = (lines, names) if units else None
        """The lines bringing Y into :attr:`outputs` at a cycle's end, and their names (None: no outputs)."""
        self._y_keys = [0] * units
        """Each unit of outputs' registers as the outputs hold them (see :func:`.symbols.publisher`)."""
        self._publish_outputs = function("c", lines, {**names, "aY": pad.areas["Y"]}) if units else None
        inputs = [self.symbols[n] for n in self.input_names]
        self._read_terminals = reader(self.terminals, inputs)
        self._aliased_inputs = overlapping(inputs)
        self._sample = sampler(inputs, "tX") if not self._aliased_inputs else ([], {})
        """The lines storing the input levels into the terminals, and their names (none if two inputs overlap)."""
        self._load_terminals = function("levels", self._sample[0], {**self._sample[1], "tX": self.terminals.areas["X"]})
        self._writes_x = any(
            i.mnemonic in ("WR", "WRC", "PUT", "SET", "RES", "LET") and getattr(i.arg, "area", "") == "X"
            for i in self.machine.asm.code  # type: ignore[union-attr]
        )
        """The program writes X: the turnaround must restore the image from the terminals every cycle."""
        self._fresh_terminals = True
        """Two input names share a terminal: only the one the wiring changed may write it."""
        self._input_levels = _tuple_getter(self.input_names)
        self._last_inputs = self._input_levels(self.inputs)

    def _off(self, name: str) -> Any:
        return False if self.symbols[name].width == "bit" else 0

    # -- modes ----------------------------------------------------------------------------------

    def start(self, restart: str | None = None) -> None:
        """STOP -> RUN by a ``cold`` restart (R cleared, P63 in the first cycle) or a ``warm`` one
        (the retentive part of R kept, P62 in the first cycle). By default the first start after a
        download is cold and a later one (a mode switch) warm, as an S7 keeps its retain tags."""
        if self.machine is None:
            raise ConfigurationError("no program is loaded; call cpu.load(program) first")
        if restart is None:
            restart = "warm" if self._started else "cold"
        if restart not in ("cold", "warm"):
            raise ConfigurationError(f"restart {restart!r}: use 'cold' or 'warm'")
        if self.mode == RUN:
            return
        getattr(self.machine, restart)()
        self._fresh_terminals = True  # the restart cleared X and U: sample them in the first cycle
        self._restart = restart
        self._started = True
        self.mode = RUN
        self._pending = None
        self._next_start = self.clock.now
        self._periods = self.config.p5_p9_ns
        self._due = [self.clock.now + p for p in self._periods]
        self._only_p0 = set(self.machine.asm.processes) <= {0, 60}
        self._cycle_ns = self.config.cycle_ns
        self.events_raised.clear()
        self._diag("STOP->RUN", f"{restart} restart: the CPU switched to RUN")

    def stop(self, reason: str = "requested") -> None:
        """RUN -> STOP: no cycle runs and the outputs are switched off."""
        was = self.mode
        self.mode = STOP
        self._pending = None
        self.outputs = {n: self._off(n) for n in self.output_names}
        self._y_keys[:] = [0] * len(self._y_keys)  # every output off
        self.output_version += 1
        if was == RUN:
            self._diag("RUN->STOP", f"the CPU switched to STOP ({reason})")

    def power_cycle(self) -> None:
        """Power off and on: a warm restart (the retentive part of R survives). A cycle the cut
        interrupts keeps what it did; :attr:`cut` reports it, so the trace has its row."""
        interrupted = self.scan_start_ns if self._pending is not None else None
        self.stop(reason="power off")
        if interrupted is not None and self.cut.call is not None:
            self.cut.call(self, TASK, interrupted)
        self.start("warm")

    def raise_event(self, source: int) -> None:
        """Interrupt source 1..8: P(40 + source) runs at the next turnaround if S29.(source - 1) enables it."""
        if not 1 <= source <= 8:
            raise ConfigurationError(f"interrupt source {source}: the sources are 1..8 (P41..P48)")
        self.events_raised.add(source)

    def interrupt(self, source: str) -> None:
        """The scenario verb ``interrupt``: :meth:`raise_event` for the source named ``"1"`` .. ``"8"``."""
        self.raise_event(int(source))

    def set_time_of_day(self, text: str) -> None:
        """The scenario verb ``set_clock``: the clock set to ``"HH:MM:SS"`` of its current day."""
        moment = _dt.datetime.combine(self.local_time().date(), _dt.time.fromisoformat(text))
        self.set_clock(moment)

    # -- host access ----------------------------------------------------------------------------

    def set_input(self, name: str, value: Any) -> None:
        """Drive an input terminal, by symbol (``"START"``) or by address (``"X0.0"``, ``"X1"``, ``"XW0"``)."""
        if name in self.inputs:
            self.inputs[name] = value
            return
        try:
            op = parse_address(name)
        except OperandError:
            op = None
        if op is None or op.area != "X":
            raise UnknownTagError(f"no input {name!r}{did_you_mean(name, self.inputs)}; or name an address X0.0")
        self.terminals.check(op)
        write(self.terminals, op, int(value))
        self._refresh_inputs()
        self._fresh_terminals = True

    def _refresh_inputs(self) -> None:
        """Every input symbol as the terminals hold it (two names on one terminal agree)."""
        levels = dict(zip(self.input_names, self._read_terminals(), strict=True))
        self.inputs.update(levels)
        self.image_in.update(levels)  # (the property first applies the last sample, which this one replaces)
        self._last_inputs = self._input_levels(self.inputs)

    def write(self, name: str, value: Any) -> None:
        """Write a symbol or an address (``"R10"``, ``"RW0"``) in the scratchpad now (an HMI write)."""
        op = self._operand(name)
        try:
            self.machine.pad.check(op)  # type: ignore[union-attr]
        except OperandError as exc:
            raise ConfigurationError(f"cannot write {name}: {exc}") from None
        write(self.machine.pad, op, int(value))  # type: ignore[union-attr]
        if getattr(op, "area", "") in ("X", "U"):  # the input image: the next turnaround samples it again (tecomat.md)
            self._fresh_terminals = True

    def peek(self, name: str) -> int:
        """A symbol's or an address's value in the scratchpad now (a bit as 0/1)."""
        return read(self.machine.pad, self._operand(name))  # type: ignore[union-attr]

    def _operand(self, name: str) -> Operand:
        if name in self.symbols:
            return self.symbols[name]
        try:
            return parse_address(name)
        except OperandError:
            raise UnknownTagError(f"no symbol or address {name!r}{did_you_mean(name, self.symbols)}") from None

    def set_clock(self, moment: _dt.datetime) -> None:
        """Set the real-time clock (S5..S12) to ``moment`` now; it runs on with the simulated time."""
        self._set_rtc_base(moment - _dt.timedelta(microseconds=self.clock.now // 1000))

    def _set_rtc_base(self, base: _dt.datetime) -> None:
        """The clock reads ``base`` at time 0; S5..S12 are computed from the microseconds since its midnight."""
        self._rtc_base = base
        self._rtc_base_us = ((base.hour * 60 + base.minute) * 60 + base.second) * 1_000_000 + base.microsecond
        self._rtc_day: int | None = None
        self._rtc_date = b""
        self._rtc_until = 0

    def local_time(self) -> _dt.datetime:
        """The real-time clock now."""
        return self._rtc_base + _dt.timedelta(microseconds=self.clock.now // 1000)

    # -- running --------------------------------------------------------------------------------

    @property
    def now(self) -> int:
        """The simulated time now, in ns."""
        return self.clock.now

    def run(self, duration: str | int) -> None:
        """Run for a duration (``"10s"`` or ns)."""
        self.run_until(self.clock.now + to_ns(duration))

    def scan(self, count: int = 1) -> None:
        """Run ``count`` whole cycles; the clock stops at the last one's end."""
        head, m = self._head, self.machine
        if (  # one cycle of a program of P0 alone: the loop below would make one call of the head
            count == 1
            and head is not None
            and self._pending is None
            and self.mode == RUN
            and m.code[self._p0] is head  # type: ignore[union-attr]
            and m.pass_no  # type: ignore[union-attr]
            and not self.events_raised
        ):
            head(self._next_start)
            return
        target = self.scan_count + count
        while self.mode == RUN and self.scan_count < target:
            if self._pending is None:
                m, head = self.machine, self._head
                if head is not None and m.code[self._p0] is head and m.pass_no and not self.events_raised:  # type: ignore[union-attr]
                    head(self._next_start)
                    continue
                self._begin(self._next_start)
                if self._pending is None:  # the program stopped the CPU
                    break
            self._end()

    def next_event_ns(self) -> int:
        """When the CPU next does something (a cycle's start or end); far future in STOP."""
        if self.mode != RUN:
            return NEVER
        return max(self.clock.now, self._pending if self._pending is not None else self._next_start)

    def run_until(self, until_ns: int) -> None:
        """Run every cycle starting before ``until_ns``; write the outputs of those ending by it."""
        while self.mode == RUN:
            if self._pending is not None:
                if self._pending > until_ns:
                    break
                self._end()
            elif self._next_start < until_ns:
                m, head = self.machine, self._head
                if (
                    head is not None
                    and m.code[self._p0] is head  # type: ignore[union-attr]
                    and self._next_start + self._cycle_ns <= until_ns
                    and m.pass_no  # type: ignore[union-attr]
                    and not self.events_raised
                ):
                    head(self._next_start)  # the cycle's end too: nothing happens between them
                else:
                    self._begin(self._next_start)
            else:
                break
        if self.clock.now < until_ns:
            self.clock.now = until_ns

    def _begin(self, t0: int) -> None:
        if self.clock.now < t0:
            self.clock.now = t0
        m = self.machine
        assert m is not None
        self._turnaround(t0)
        try:
            if self._only_p0 and m.pass_no != 1 and not self.events_raised:
                m.run_process(0)  # the process plan of a program that has only P0 (and P60)
            else:
                self._processes()
        except TecomatRuntimeError as exc:
            self._fault(exc)
            return
        self.scan_start_ns = t0
        self._pending = t0 + self._cycle_ns

    def _end(self) -> None:
        end = self._pending
        assert end is not None and self.machine is not None
        self._pending = None
        clock = self.clock
        if clock.now < end:
            clock.now = end
        copies = self._take_traced()
        subscriber = self.scan_end.call
        if subscriber is None:
            self._copies = copies
        else:  # a subscriber (the recorder) reads them now, maybe from a dict it holds
            self._copies = None
            self._decode_traced(self._t.__dict__, *copies)
        if self._publish_outputs is not None:
            self._publish_outputs(self)
        self.scan_end_ns = end
        self.scan_count += 1
        self._next_start = end
        if subscriber is not None:
            subscriber(self)

    # -- the turnaround and the processes -------------------------------------------------------

    def _turnaround(self, t0: int) -> None:
        m = self.machine
        assert m is not None
        pad = m.pad
        m.turnaround(t0)
        terminals, inputs = self.terminals, self.inputs
        levels = self._input_levels(inputs)
        changed = levels != self._last_inputs
        if changed:  # the wiring (or set_input) changed some
            if self._aliased_inputs:
                self._sample_aliased()
            else:
                self._load_terminals(levels)
                self._sampled = self._last_inputs = levels
        if changed or self._writes_x or self._fresh_terminals:  # else X and U still hold what the terminals hold
            self._fresh_terminals = False
            pad.areas["X"][:] = pad.areas["U"][:] = terminals.areas["X"]
        s = pad.areas["S"]
        if t0 < self._rtc_until and m.pass_no != 1:  # S5..S19 change at most every 10 ms
            s[2] = S2_RUNNING
        else:
            self._system_registers(s, t0)

    def _sample_aliased(self) -> None:
        """Two input names share a terminal: only the one the wiring changed writes it."""
        inputs, seen = self.inputs, self.image_in
        for name in self.input_names:
            if inputs[name] != seen[name]:
                write(self.terminals, self.symbols[name], int(inputs[name]))
        self._refresh_inputs()

    def _cycle(self) -> Cycle:
        """The turnaround (:meth:`_turnaround`, the machine's part included) and the cycle's end
        (:meth:`_end`) as lines around P0 in one generated function, for a program of P0 alone (see
        :func:`plcsim.controllers.tecomat.fused.fuse`): what the CPU does between them in a cycle that runs
        only P0; ``start`` is the cycle's t0 (``t0``, ``t1`` ... name the run's locals). The lines must do
        what those methods do, step for step (the tests run both ways)."""
        m = self.machine
        assert m is not None
        stacks = "for k in stacks: k[:] = ZEROS" if self.config.clear_all_stacks else "sA[:] = ZEROS"
        loads = [*self._sample[0], "c._sampled = c._last_inputs = levels"]  # the terminals written here
        sample = ["sample()"] if self._aliased_inputs else loads
        before = [
            "if clock.now < start: clock.now = start",
            "m.prev_t0 = m.t0; m.t0 = start; m.pass_no += 1; m.jumps = 0",  # (m.calls: P0 alone calls nothing)
            stacks,
            "m.active = 0; m.st = sA",
            "levels = levels_of(c.inputs)",
            "if levels != c._last_inputs:",
            *(f"    {line}" for line in sample),
            "    c._fresh_terminals = False; aX[:] = aU[:] = tX",
            f"elif {self._writes_x} or c._fresh_terminals:",
            "    c._fresh_terminals = False; aX[:] = aU[:] = tX",
            f"if start < c._rtc_until: aS[2] = {S2_RUNNING}",
            "else: system(aS, start)",
        ]
        after = [
            "end = start + c._cycle_ns",
            "c.scan_start_ns = start",
            "if clock.now < end: clock.now = end",
            f"copies = {self._copied}",
            "subscriber = c.scan_end.call",
            "if subscriber is None: c._copies = copies",
            "else: c._copies = None; decode(values, *copies)",
        ]
        if self._publish is not None:
            after += self._publish[0]  # its aY[i] are the run's locals where it holds them
        after += [
            "c.scan_end_ns = end; c.scan_count += 1; c._next_start = end",
            "if subscriber is not None: subscriber(c)",
        ]
        names = {
            "c": self,
            "clock": self.clock,
            "sA": m.stacks[0],
            "stacks": m.stacks,
            "ZEROS": ZEROS,
            "levels_of": self._input_levels,
            "sample": self._sample_aliased,
            **self._sample[1],
            "tX": self.terminals.areas["X"],
            "system": self._system_registers,
            "decode": self._decode_traced,
            "values": self._t.__dict__,
            **(self._publish[1] if self._publish is not None else {}),
        }
        return Cycle(before, after, names)

    def _system_registers(self, s: bytearray, t0: int) -> None:
        first = self.machine.pass_no == 1  # type: ignore[union-attr]
        restart = self._restart if first else None
        s[2] = S2_RUNNING | (restart == "warm") << 3 | (restart == "cold") << 4
        day, us = divmod(self._rtc_base_us + t0 // 1000, 86_400_000_000)
        s[5], s[6], s[7], s[8] = us // 10_000 % 100, us // 1_000_000 % 60, us // 60_000_000 % 60, us // 3_600_000_000
        if day != self._rtc_day:
            self._rtc_day = day
            date = self._rtc_base.date() + _dt.timedelta(days=day)
            self._rtc_date = bytes((date.isoweekday(), date.day, date.month, date.year % 100))
        s[9:13] = self._rtc_date
        self._rtc_until = min(t0 - us % 10_000 * 1000, t0 - t0 % 10_000_000) + 10_000_000
        h = HALF_PERIODS_NS  # S13.k is 1 in the second half of each period
        s[13] = (
            t0 // h[0] & 1
            | (t0 // h[1] & 1) << 1
            | (t0 // h[2] & 1) << 2
            | (t0 // h[3] & 1) << 3
            | (t0 // h[4] & 1) << 4
            | (t0 // h[5] & 1) << 5
            | (t0 // h[6] & 1) << 6
            | (t0 // h[7] & 1) << 7
        )
        pack_into(
            "<HHH", s, 14, t0 // 100_000_000 & 0xFFFF, t0 // 1_000_000_000 & 0xFFFF, t0 // 10_000_000_000 & 0xFFFF
        )

    def local_time_at(self, t_ns: int) -> _dt.datetime:
        """The real-time clock at the simulated time ``t_ns``."""
        return self._rtc_base + _dt.timedelta(microseconds=t_ns // 1000)

    def _processes(self) -> None:
        m = self.machine
        assert m is not None
        defined = m.asm.processes
        s = m.pad.areas["S"]
        plan: list[int] = []
        if m.pass_no == 1 and self._restart is not None:
            plan.append(63 if self._restart == "cold" else 62)
        for source in sorted(self.events_raised):
            if s[self.config.event_enable_byte] >> (source - 1) & 1:
                plan.append(40 + source)
        self.events_raised.clear()
        plan.append(0)
        if self.config.p1_p4_rotation:
            plan.append(1 + (m.pass_no - 1) % 4)
        t0 = m.t0
        for k, period in enumerate(self._periods):
            if t0 >= self._due[k]:
                plan.append(5 + k)
                self._due[k] += ((t0 - self._due[k]) // period + 1) * period
        base = self.config.process_mask_byte
        mask = int.from_bytes(s[base : base + 4], "little")
        plan += [10 + k for k in range(31) if mask >> k & 1]
        for number in plan:
            if number in defined and m.run_process(number) == END_CYCLE:
                break
        else:
            if 64 in defined:
                m.run_process(64)
            return
        if 64 in defined and self.config.final_after_eoc:
            m.run_process(64)

    def _fault(self, exc: TecomatRuntimeError) -> None:
        m = self.machine
        assert m is not None
        where, line = "", None
        if exc.index is not None:
            instr = m.asm.code[exc.index]
            where, line = f"{m.asm.filename}, line {instr.line}: ", instr.line
            task = f"P{instr.process}"
        else:
            task = None
        self._diag("error in the program", f"{where}{exc}", task=task, line=line)
        self.stop(reason="error in the program")

    def _diag(self, event: str, message: str, task: str | None = None, line: int | None = None) -> None:
        self.diagnostics.append(DiagnosticEntry(self.clock.now, event, message, task, None, line))

    @property
    def error(self) -> DiagnosticEntry | None:
        """The entry that last stopped the CPU, if an error did."""
        if self.mode == RUN:
            return None
        for entry in reversed(self.diagnostics):
            if entry.event == "error in the program":
                return entry
            if entry.event == "STOP->RUN":
                return None
        return None

    # -- inspection -----------------------------------------------------------------------------

    @property
    def stack(self) -> list[int]:
        """The active stack, A0 first."""
        return list(self.machine.st)  # type: ignore[union-attr]

    def __repr__(self) -> str:
        prog = self.program.filename if self.program else "no program"
        return f"<TecomatCPU {self.mode} t={self.clock.now}ns cycles={self.scan_count} {prog}>"


def _tuple_getter(names: list[str]) -> Any:
    """``d -> (d[n1], d[n2], ...)`` at C speed, a tuple also for one name (or none)."""
    if len(names) == 1:
        name = names[0]
        return lambda d: (d[name],)
    return itemgetter(*names) if names else (lambda d: ())


def _parse_rtc(text: str) -> _dt.datetime:
    try:
        date, _, clock = text.rpartition("-")
        return _dt.datetime.fromisoformat(f"{date}T{clock}")
    except ValueError:
        raise ConfigurationError(f"rtc_start {text!r}: write 'YYYY-MM-DD-HH:MM:SS'") from None


def load_file(path: str | Path, **options: Any) -> TecomatCPU:
    """A Tecomat CPU running the ``.il`` file at ``path``."""
    path = Path(path)
    return TecomatCPU(path.read_text(encoding="utf-8"), filename=str(path), **options)
