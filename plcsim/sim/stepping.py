"""The fused step: wiring in, one OB1 scan and its trace row in one call, for the common case of a co-simulation.

Almost every physics step of a recorded co-simulation does the same: the sensors are copied to the inputs, the
S7 CPU runs exactly one OB1 scan that starts at the step and lasts it, and the recorder writes that scan's row.
Through the general path that is a call of the wiring, :meth:`~plcsim.controllers.s7.cpu.CPU.run_until` (which
runs the CPU's fused scan, then asks what else is due), the recorder's hook called by the CPU, and a packed
head per row. :func:`fused_step` is the CPU's own fused scan (:meth:`~plcsim.controllers.s7.cpu.CPU.fused_scan`)
with the wiring's copy at its start and the row at its end: the same operations in the same order, so the
trace is the same bit for bit. Its row keeps its start time alone as its head (a regular row of
:class:`~plcsim.trace.rows.RunLengthRows`).

The scan declines, having touched nothing, whatever it cannot do whole (a scan that does not end at the step's
end, STOP, an unfinished scan, an interrupt or a force, another program since it was built); the simulation
then takes the general path. A wiring with a fault has no fused step (its copy depends on the time and the
faults): build it again when an action may have changed the faults or the program.
"""

from __future__ import annotations

from typing import Any

from plcsim.controllers.s7.fused import FusedScan


def fused_step(cpu: Any, wiring: Any, recorder: Any) -> FusedScan | None:
    """``step(until_ns)``: the wiring's copy, then the CPU's next OB1 scan if it ends at ``until_ns``, with its
    trace row; whether the scan ran (after a scan that left the CPU in STOP, the rest of the step is the CPU's
    :meth:`run_until`). None for a controller without fused scans, a program whose scans are not fused, or a
    wiring with a fault."""
    build = getattr(cpu, "fused_scan", None)
    if build is None or (wiring is not None and wiring.faulted):
        return None
    after = replaces = None
    if recorder.scan_hook is not None and not recorder.changes_only and cpu.fixed_cycle_ns:
        after, replaces = recorder.regular_row(cpu.fixed_cycle_ns, cpu.scan_task_number), recorder.scan_hook
    return build(wiring.step_inputs if wiring is not None else None, after, replaces, fills=True)
