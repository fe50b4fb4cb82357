"""The fused step: wiring in, one OB1 scan and its trace row in one call, for the common case of a co-simulation.

Almost every physics step of a recorded co-simulation does the same: the sensors are copied to the inputs, the
S7 CPU runs exactly one OB1 scan that starts at the step and lasts it (a fixed cycle equal to the physics step,
no interrupts), and the recorder writes that scan's row. Through the general path that is a call of the wiring,
:meth:`~plcsim.controllers.s7.cpu.CPU.run_until` (which resumes the CPU's scheduling loop and asks it what is
due), the recorder's hook called by the CPU, and a packed head per row. :func:`fused_scan` does the same work
in one function: the same operations on the same state in the same order (the CPU's own fast path,
``TaskRunner._cyclic_loop``, with nothing due but that one scan), so the trace is the same bit for bit. Its row
keeps its start time alone as its head (a regular row of :class:`~plcsim.trace.rows.RunLengthRows`).

It does a step only when that is provably all the step holds, checked before anything is touched: the CPU in
RUN with no unfinished execution, OB1 due exactly at the step, no clock memory bit due, no force, the wiring
without faults, the recorder the only subscriber of the scan's end. Otherwise (and in STOP, on a download,
with interrupts or a scan longer than the step) it declines and the simulation takes the general path.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from plcsim.controllers.protocol import RUN
from plcsim.core.clock import NEVER
from plcsim.trace.rows import BLOCK, UNPACKABLE


def fused_scan(cpu: Any, wiring: Any, recorder: Any, dt_ns: int) -> Callable[[int], bool] | None:
    """A function doing the CPU's part of the physics step at ``t`` (wiring in, the scan, its row) and returning
    True, or returning False having touched nothing when the step needs the general path; None when this CPU,
    wiring and recorder never allow it (another controller, interrupts, a cycle other than ``dt_ns``).

    Build it again after a download (the CPU's plan of its scan changes; the function then declines)."""
    plan = getattr(cpu, "_cyclic_plan", None)
    if plan is None or wiring is None or recorder.changes_only or recorder.scan_hook is None:
        return None
    fixed, whole, aliased_inputs = plan
    if fixed != dt_ns or whole is None or aliased_inputs or cpu._interrupts:
        return None
    copy, hook, scan_end = wiring._copy_inputs, recorder.scan_hook, cpu.scan_end
    ex, stack, clock, ticks = cpu._ob1.execution, cpu._stack, cpu.clock, cpu._ticks
    tags = cpu.t
    d, inputs = tags.__dict__, cpu.inputs
    out_getter, output_names = cpu._out_getter, cpu.output_names
    rows = recorder.trace.row_sink()
    heads, values_at, changes, last, pack, add = rows.heads, rows.values, rows.changes, rows.last, rows.pack, rows.add
    packed_row, row = recorder.packed_row, recorder.row
    task = cpu.scan_task_number
    rows.set_regular(dt_ns, task)
    regular = rows.regular

    def scan(t: int) -> bool:
        if (
            cpu._ob1_next != t
            or clock.now > t
            or cpu.mode != RUN
            or stack
            or t >= cpu._clock_next
            or cpu.forces
            or wiring.step_inputs is not copy
            or scan_end.call is not hook
            or cpu._cyclic_plan is not plan
            or rows.regular is not regular
        ):
            return False
        copy(inputs, t)
        # -- TaskRunner._cyclic_loop's scan, nothing else being due --
        clock.now = t
        ticks[0] = 0
        d.update(inputs)
        cpu.image_in = image = inputs.copy()
        cpu.scan_start_ns = t
        try:
            whole(tags)
        except KeyboardInterrupt:
            raise
        except BaseException as exc:  # noqa: BLE001 - the CPU sorts it out, as its own loop does
            cpu._push_scan(t, fixed)
            cpu._after_exception(ex, exc, NEVER)
            cpu.run_until(t + dt_ns)  # the rest of the step as the CPU's loop goes on after an error
            return True
        end = t + fixed
        clock.now = end
        values = out_getter(d)
        if values != cpu._last_out:
            cpu._last_out = values
            cpu.outputs.update(zip(output_names, values))
            cpu.output_version += 1
        cpu._ob1_next = cpu.scan_end_ns = end
        cpu.scan_count += 1
        # -- the recorder's row (Recorder._fast_on_scan), its head the start time alone --
        try:
            packed = packed_row(d, image)
        except UNPACKABLE:  # a value its column cannot hold: the general path keeps the row as it is
            add(t, end, task, row(d, image))
        else:
            heads.append(t)
            if packed != last[0]:
                last[0] = packed
                changes.append(len(heads) - 1)
                values_at.append(packed)
            if len(heads) >= BLOCK:
                pack()
        if cpu._first_scan or cpu._diag_changed:
            cpu._first_scan = cpu._diag_changed = False
            cpu._set_system_bits()
        return True

    return scan
