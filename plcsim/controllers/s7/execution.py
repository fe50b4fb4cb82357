"""Task execution: OB1 scans, cyclic interrupts pre-empting between networks, process images, clock
and system memory, faults. The scheduling half of :class:`plcsim.controllers.s7.cpu.CPU` (the timing model is in
its module docstring).
"""

from __future__ import annotations

import operator
import random
import traceback
from bisect import bisect_left
from collections.abc import Callable
from typing import Any

from plcsim.controllers.loaded import SourceProgram, TaskSpec, student_names
from plcsim.controllers.protocol import RUN
from plcsim.controllers.s7.config import CLOCK_BITS, CPUConfig
from plcsim.controllers.s7.fused import FusedScan, fused_scan
from plcsim.controllers.s7.instructions.system import JumpTo, ReturnFromBlock
from plcsim.core.clock import NEVER, Clock
from plcsim.core.errors import PlcError
from plcsim.core.observers import Subscribers
from plcsim.tags.values import PlcStruct, store


class CycleWatchdog(Exception):  # noqa: N818 - it is the S7 name of the event
    """The program looped inside one task execution past the watchdog budget."""


class RunningTask:
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
        "number",
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
        self.period_ns, self.phase_ns = spec.period_ns or 0, spec.phase_ns
        self.number = spec.number
        self.duration_ns = spec.duration_ns
        self.next_due = 0
        self.inputs: list[str] = []
        self.outputs: list[str] = []
        self.offsets: dict[int, list[int]] = {}
        self.execution = Execution(self)

    def network_offsets(self, duration: int, cost: int | None) -> list[int]:
        """Where in an execution of ``duration`` each network sits (for pre-emption between networks)."""
        offsets = self.offsets.get(duration)
        if offsets is None:
            n = self.n
            offsets = [k * cost for k in range(n)] if cost else [(k * duration) // n for k in range(n)]
            self.offsets[duration] = offsets
        return offsets


class Execution:
    """The running execution of a task: start, duration, next network, time lost to pre-emption."""

    __slots__ = ("task", "t0", "duration", "offsets", "index", "shift", "paused_at")

    def __init__(self, task: RunningTask):
        self.task = task
        self.t0 = self.duration = self.index = self.shift = 0
        self.paused_at = -1
        self.offsets: list[int] = []

    def next_time(self) -> int:
        if self.index < self.task.n:
            return self.t0 + self.shift + self.offsets[self.index]
        return self.t0 + self.shift + self.duration


class TaskRunner:
    """The scheduling methods of the CPU (a mixin: the state lives in :class:`plcsim.controllers.s7.cpu.CPU`, which sets
    every attribute declared here in its ``__init__`` and ``load``)."""

    # the CPU's public state this half reads and writes
    config: CPUConfig
    clock: Clock
    mode: str
    t: PlcStruct
    inputs: dict[str, Any]
    outputs: dict[str, Any]
    forces: dict[str, Any]
    image_in: dict[str, Any]
    input_names: list[str]
    output_names: list[str]
    scan_end: Subscribers
    task_end: Subscribers
    scan_count: int
    scan_start_ns: int
    scan_end_ns: int
    output_version: int
    program: SourceProgram | None
    # the CPU's private state: executions, the plan of OB1's fast path, the output image's last values
    _stack: list[Execution]
    _ob1: RunningTask
    _interrupts: list[RunningTask]
    _next_irq: int
    _ob1_next: int
    _first_scan: bool
    _diag_changed: bool
    _clock_next: int
    _ticks: list[int]
    _cyclic_plan: tuple[int, Callable[[Any], None] | None, bool]
    _cyclic: Any
    _fused: FusedScan | None
    _out_getter: Callable[[dict[str, Any]], tuple[Any, ...]]
    _last_out: tuple[Any, ...]
    _aliased_inputs: list[str]
    _plain_inputs: list[str]
    _rng: random.Random
    # the CPU's methods it calls (annotations only: a stub here would hide HostAccess's)
    stop: Callable[..., None]
    resolve_path: Callable[[str], tuple[Any, Any]]
    _diag: Callable[..., None]

    def _run(self, until_ns: int, scan_target: int | None) -> None:
        if self._interrupts:
            self._run_preemptive(until_ns, scan_target)
        else:
            self._run_cyclic(until_ns, scan_target)

    def _run_preemptive(self, until_ns: int, scan_target: int | None) -> None:
        """Run OB1 and the interrupts, which pre-empt between networks (the timing model of
        :mod:`plcsim.controllers.s7.cpu`)."""
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
        """:meth:`_run_preemptive` for a program without interrupts: the same events, faster (see
        :meth:`_cyclic_loop`). A call made while the loop runs (from a subscriber of :attr:`scan_end`) gets a
        loop of its own, as a nested call of a plain method would."""
        loop = self._cyclic
        if loop is None or loop.gi_running:
            loop = self._new_cyclic_loop(nested=loop is not None)
        try:
            loop.send((until_ns, scan_target))
        except BaseException:  # the loop has ended with it: the next call starts a new one
            if loop is self._cyclic:
                self._cyclic = None
            raise

    def _new_cyclic_loop(self, nested: bool = False) -> Any:
        loop = self._cyclic_loop()
        next(loop)
        if not nested:
            self._cyclic = loop
        return loop

    def _cyclic_loop(self) -> Any:
        """The body of :meth:`_run_cyclic`: a generator that runs the events up to each ``(until_ns, scan_target)``
        sent to it. Kept between the calls, it reads what it needs from the CPU once per download instead of
        at every 1 ms step (a new one is made by :meth:`_plan_cyclic`; the forces, the mode and the scan's
        state are read at each scan as before).

        The two marked blocks are :meth:`_begin_scan` and :meth:`_end_scan` written out: calling them
        instead cost 3 % of the PLC-only rate (1014 -> 1045 Python opcodes per scan of the 25-network
        workload, 156 k -> 151 k scans per CPU-second; an earlier fold cost 4.9 %). A scan that runs its
        whole program in one call and ends within ``until_ns`` never goes on the stack: nothing can look at
        the stack while it runs (its execution state is set up only when the scan stays unfinished or the
        call raises), which saves a tenth of the loop's opcodes. A test runs each workload through both
        paths and asks for the same trace, so the copies cannot drift apart."""
        task = self._ob1
        ex = task.execution
        stack = self._stack
        clock = self.clock
        ticks = self._ticks
        n = task.n
        t = self.t
        d = t.__dict__
        inputs = self.inputs
        scan_end = self.scan_end
        fixed, whole, aliased_inputs = self._cyclic_plan
        out_getter, output_names = self._out_getter, self.output_names
        while True:
            until_ns, scan_target = yield
            while self.mode == RUN:
                if stack:  # a scan left unfinished: its remaining networks, or its end
                    if ex.index < n:
                        self._run_networks(ex, NEVER)
                        if ex.index < n or self.mode != RUN:
                            break
                    end = ex.t0 + ex.shift + ex.duration
                    if end > until_ns:
                        break
                    stack.pop()
                else:
                    t0 = self._ob1_next
                    if t0 >= until_ns:
                        break
                    # -- _begin_scan(t0) --
                    if t0 < clock.now:
                        t0 = clock.now
                    clock.now = t0
                    ticks[0] = 0
                    if t0 >= self._clock_next:
                        self._latch_clock_memory(t0)
                    if aliased_inputs or self.forces:
                        self._refresh_inputs(task)
                    else:
                        d.update(inputs)
                        self.image_in = inputs.copy()
                    duration = fixed or self._cycle_duration(task)
                    self.scan_start_ns = t0
                    # -- end of _begin_scan (the execution goes on the stack only when it must) --
                    if whole is None:
                        self._push_scan(t0, duration)
                        continue
                    try:
                        whole(t)
                    except KeyboardInterrupt:
                        raise
                    except BaseException as exc:  # noqa: BLE001 - sorted out in _after_exception
                        self._push_scan(t0, duration)
                        self._after_exception(ex, exc, NEVER)
                        continue
                    end = t0 + duration
                    if end > until_ns:
                        self._push_scan(t0, duration).index = n
                        break
                if end > clock.now:
                    clock.now = end
                # -- _end_scan(end) --
                if self.forces:
                    self._apply_forces()
                values = out_getter(d)
                if values != self._last_out:
                    self._last_out = values
                    self.outputs.update(zip(output_names, values))
                    self.output_version += 1
                self._ob1_next = self.scan_end_ns = end
                self.scan_count += 1
                if scan_end.call is not None:
                    scan_end.call(self)
                if self._first_scan or self._diag_changed:
                    self._first_scan = self._diag_changed = False
                    self._set_system_bits()
                # -- end of _end_scan --
                if scan_target is not None and self.scan_count >= scan_target:
                    break
                if end >= until_ns and not stack:  # the next scan starts after the call (what the top would find)
                    break

    def _push_scan(self, t0: int, duration: int) -> Execution:
        """Put OB1's execution from ``t0`` on the stack, its networks not run yet (the end of :meth:`_begin_scan`)."""
        task = self._ob1
        ex = task.execution
        if duration != ex.duration or not ex.offsets:
            ex.offsets = task.network_offsets(duration, self.config.network_cost_ns)
        ex.t0, ex.duration, ex.index, ex.shift, ex.paused_at = t0, duration, 0, 0, -1
        self._stack.append(ex)
        return ex

    def _plan_cyclic(self) -> None:
        """What :meth:`_run_cyclic` needs that changes only with a download: the fixed cycle (0 if it
        varies), the one function running all of OB1's networks, whether inputs alias other tags."""
        cfg, task = self.config, self._ob1
        fixed = 0 if cfg.jitter_ns or cfg.network_cost_ns else max(cfg.cycle_ns, cfg.min_cycle_ns)
        whole = task.merged if task.merged is not None else (task.networks[0] if task.n == 1 else None)
        self._cyclic_plan = (fixed, whole, bool(self._aliased_inputs))
        self._new_cyclic_loop()
        self._fused = fused_scan(self)  # type: ignore[arg-type]

    def _preemption_time(self, priority: int) -> int:
        return min((t.next_due for t in self._interrupts if t.priority > priority), default=NEVER)

    def _due_interrupt(self, before: int, priority: int) -> RunningTask | None:
        for task in self._interrupts:  # sorted by priority, highest first
            if task.next_due <= before and task.priority > priority:
                return task
        return None

    def _cycle_duration(self, task: RunningTask) -> int:
        cfg = self.config
        if task.kind != "cyclic":
            return task.duration_ns or 0
        base = cfg.network_cost_ns * max(1, task.n) if cfg.network_cost_ns else cfg.cycle_ns
        if cfg.jitter_ns:
            base += self._rng.randint(-cfg.jitter_ns, cfg.jitter_ns)
        return max(base, cfg.min_cycle_ns, 1)

    def _begin(self, task: RunningTask, t0: int) -> None:
        clock = self.clock
        if t0 < clock.now:
            t0 = clock.now
        if task.kind == "cyclic":  # OB1 pre-empts nothing: the stack is empty
            self._begin_scan(t0)
            return
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
            ex.offsets = task.network_offsets(duration, None)
        ex.t0, ex.duration, ex.index, ex.shift, ex.paused_at = t0, duration, 0, 0, -1
        self._stack.append(ex)

    def _begin_scan(self, t0: int) -> Execution:
        """Start an OB1 execution at ``t0`` (not before now): the clock memory, the whole input image,
        the scan's duration and network boundaries."""
        task = self._ob1
        self.clock.now = t0
        self._ticks[0] = 0
        if t0 >= self._clock_next:
            self._latch_clock_memory(t0)
        fixed, _, aliased_inputs = self._cyclic_plan
        if aliased_inputs or self.forces:
            self._refresh_inputs(task)
        else:  # the whole image at once (what _refresh_inputs does, without its questions)
            inputs = self.inputs
            self.t.__dict__.update(inputs)
            self.image_in = inputs.copy()
        duration = fixed or self._cycle_duration(task)
        self.scan_start_ns = t0
        return self._push_scan(t0, duration)

    def _advance_interrupt(self, task: RunningTask, start: int) -> None:
        due = task.next_due + task.period_ns
        if due <= start:
            missed = (start - task.next_due) // task.period_ns
            self._diag(
                "cyclic interrupt overrun", f"{task.name} could not run on time; {missed} call(s) lost", task=task.name
            )
            due = task.next_due + (missed + 1) * task.period_ns
        task.next_due = due
        self._next_irq = min(t.next_due for t in self._interrupts)

    def _run_networks(self, ex: Execution, limit: int) -> None:
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
        except KeyboardInterrupt:  # the person at the host pressed Ctrl-C: not the program's fault
            raise
        except BaseException as exc:  # noqa: BLE001 - any error of a student's (RecursionError, SystemExit ...) is a STOP
            ex.index = k
            self._run_failed(ex, exc)
        finally:
            if host_now > clock.now:
                clock.now = host_now

    def _after_exception(self, ex: Execution, exc: BaseException, until_ns: int) -> None:
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
        except KeyboardInterrupt:
            raise
        except BaseException as problem:  # noqa: BLE001 - a student's error must not crash the host
            self._run_failed(ex, problem)

    def _run_failed(self, ex: Execution, exc: BaseException) -> None:
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
            self._fault(task, k, "error in the program", describe_error(exc), exc)

    def _jump_target(self, task: RunningTask, jump: JumpTo) -> int:
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

    def _network_of(self, task: RunningTask, exc: BaseException, default: int) -> int:
        """The network whose code raised ``exc`` (found by line, since merged networks share a frame)."""
        line = program_line(exc, self.program.filename) if self.program else None
        if line is None:
            return default
        for index, (first, last) in enumerate(task.spans):
            if first <= line <= last:
                return index
        return default

    def _run_atomic(self, task: RunningTask, t0: int) -> None:
        self._begin(task, t0)
        ex = self._stack[-1]
        self._run_networks(ex, NEVER)
        if self.mode == RUN:
            ex.duration = 0
            self._end(ex)

    def _end(self, ex: Execution) -> None:
        stack = self._stack
        stack.pop()
        end = ex.t0 + ex.shift + ex.duration
        if end > self.clock.now:
            self.clock.now = end
        task = ex.task
        if task.kind == "cyclic":  # nothing is below OB1
            self._end_scan(end)
            return
        self._write_partition(task)
        if stack:
            below = stack[-1]
            below.shift += end - below.paused_at
        if self.task_end.call is not None:
            self.task_end.call(self, task.name, ex.t0, end)

    def _end_scan(self, end: int) -> None:
        """End an OB1 execution at ``end`` (popped, the clock there): all outputs, the scan's count and
        subscribers, the system bits of the next scan."""
        if self.forces:
            self._apply_forces()
        values = self._out_getter(self.t.__dict__)
        if values != self._last_out:
            self._last_out = values
            self.outputs.update(zip(self.output_names, values))
            self.output_version += 1
        self._ob1_next = self.scan_end_ns = end
        self.scan_count += 1
        if self.scan_end.call is not None:
            self.scan_end.call(self)
        if self._first_scan or self._diag_changed:
            self._first_scan = self._diag_changed = False
            self._set_system_bits()

    def _fault(self, task: RunningTask, k: int, event: str, message: str, exc: BaseException | None) -> None:
        network = task.titles[k] if k < task.n else None
        line = program_line(exc, self.program.filename) if exc is not None and self.program else None
        if line is None and k < len(task.spans):  # a front end whose networks run no code of the file: its span
            line = task.spans[k][0] or None
        where = (
            f"{task.name} network {k + 1}" + (f" ({network})" if network else "") + (f", line {line}" if line else "")
        )
        self._diag(
            event, f"{where}: {message}", task=task.name, network=f"{k + 1} ({network})" if network else None, line=line
        )
        self.stop(reason=f"{event} in {task.name}")

    # -- process images -----------------------------------------------------------------------

    def _refresh_inputs(self, task: RunningTask) -> None:
        """Read the task's inputs into the process image, and keep what was delivered (``image_in``): the
        trace records that, so a program that writes an input changes its image, never its record."""
        d = self.t.__dict__
        inputs = self.inputs
        if task.kind == "cyclic":
            if self._aliased_inputs:
                for name in self._plain_inputs:
                    d[name] = inputs[name]
                for name in self._aliased_inputs:
                    store(self.t, name, inputs[name])
            else:
                d.update(inputs)
        else:
            for name in task.inputs:
                store(self.t, name, inputs[name])
        if self.forces:
            self._apply_forces()
        if task.kind == "cyclic":
            self.image_in = {name: d[name] for name in self.input_names}
        else:  # a partition: the other inputs stay as delivered at their last refresh
            self.image_in.update((name, d[name]) for name in task.inputs)

    def _refresh_inputs_stopped(self) -> None:
        for name in self.input_names:
            store(self.t, name, self.inputs[name])
        self.image_in = {name: self.t.__dict__[name] for name in self.input_names}

    def _write_partition(self, task: RunningTask) -> None:
        """Write the outputs an interrupt or startup task uses (OB1 writes all of them: :meth:`_end_scan`)."""
        if self.forces:
            self._apply_forces()
        if not task.outputs:
            return
        d = self.t.__dict__
        changed = False
        for name in task.outputs:
            if self.outputs[name] != d[name]:
                self.outputs[name] = d[name]
                changed = True
        if changed:
            self._last_out = self._out_getter(self.outputs)
            self.output_version += 1

    def _switch_outputs_off(self) -> None:
        off = {name: switched_off(value) for name, value in self.outputs.items()}
        if off != self.outputs:
            self.outputs = off
            self.output_version += 1
        self._last_out = self._out_getter(off)

    def _apply_forces(self) -> None:
        for name, value in self.forces.items():
            container, key = self.resolve_path(name)
            store(container, key, value)
            if name in self.outputs:
                self.outputs[name] = self.t.__dict__[name]

    # -- clock and system memory ----------------------------------------------------------------

    def _latch_clock_memory(self, now: int) -> None:
        if self.config.clock_memory_byte is None:
            self._clock_next = NEVER
            return
        ms = now // 1_000_000
        nxt = NEVER
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


def switched_off(value: Any) -> Any:
    if isinstance(value, bool):
        return False
    if isinstance(value, float):
        return 0.0
    if isinstance(value, int):
        return 0
    return value


def tuple_getter(names: list[str]) -> Callable[[dict[str, Any]], tuple[Any, ...]]:
    """The values of ``names`` in a mapping as one tuple, taken in C: the output image's compare and write at
    every scan end. One name is taken twice, ``(v, v)``: ``itemgetter`` gives a bare value for one name, and a
    Python function making it a 1-tuple cost a call per scan; zipped with the one name, the pair writes it once.
    Every tuple the image is compared with (the CPU's ``_last_out``) comes from this getter."""
    if not names:
        return lambda d: ()
    return operator.itemgetter(*names) if len(names) > 1 else operator.itemgetter(names[0], names[0])


def describe_error(exc: BaseException) -> str:
    text = str(exc)
    name = type(exc).__name__
    if isinstance(exc, PlcError):
        return text
    if isinstance(exc, RecursionError):
        return f"{name}: {text} (a network or function calls itself, directly or through another, without end)"
    if isinstance(exc, NameError):  # (UnboundLocalError too) a local of merged networks, in the program's name
        text = student_names(text)
    return f"{name}: {text}" if text else name


def program_line(exc: BaseException, filename: str) -> int | None:
    for frame in reversed(traceback.extract_tb(exc.__traceback__)):
        if frame.filename == filename:
            return frame.lineno
    return None
