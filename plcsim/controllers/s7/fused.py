"""One OB1 scan in one call: the common case of the scan loop, fused into one function per download.

The general loops of :class:`~plcsim.controllers.s7.execution.TaskRunner` decide at every event what comes
next (an interrupt, a network, the end of an execution), which costs more than a whole 25-network program
runs in. Most scans have nothing to decide: no interrupt falls inside them, nothing is forced, the cycle is
fixed and the task runs in one call (its networks merged). :func:`fused_scan` builds, at each download, one
function that runs such a scan from its start to its end: clock memory, the input image, the program, the
output image, the count, the subscriber, the system bits, exactly the statements the general loop runs for
it in the same order, with what changes only with a download bound once. Before it changes anything it
checks that the scan is one of those; if not it returns False and the caller takes the general loop, which
then finds the CPU as it was.

What the general loop does for the rest stays its own: an interrupt due before the scan's end (OB30
pre-empts between networks and before the output write), a scan a host step ends in the middle of, a
jitter or a network cost, forces, inputs that alias other tags. An error in the program goes to the same
handler as in the general loop (a JMP goes on network by network, a fault names its network and line and
sends the CPU to STOP); the watchdog's count is reset at the scan's start as there.

A co-simulation's step (:mod:`plcsim.sim.stepping`) is this scan with the host's work at its two ends (the
wiring's copy of the sensors before the input image is read, the trace row at the end), so that the scan's
start and end are written once, here.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING, Any

from plcsim.controllers.protocol import RUN
from plcsim.core.clock import NEVER

if TYPE_CHECKING:
    from plcsim.controllers.s7.cpu import CPU

FusedScan = Callable[[int], bool]
"""``scan(until_ns)``: run the next OB1 scan whole if it starts before and ends at or before ``until_ns``
and nothing else can happen in it; whether it ran."""

InputsIn = Callable[[dict[str, Any], int], None]
"""``before(inputs, t0)``: fill the CPU's input terminals just before a scan from ``t0`` reads them."""

ScanRow = Callable[[int, int], None]
"""``after(t0, end)``: what a subscriber of the scan's end does, given the scan's start and end."""


def fused_scan(
    cpu: CPU, before: InputsIn | None = None, after: ScanRow | None = None, replaces: Any = None, fills: bool = False
) -> FusedScan | None:
    """The fused scan of ``cpu``'s loaded program, or None where no scan can be fused (a varying cycle, a
    task that runs network by network, inputs that alias other tags; or ``fuse=False`` in the configuration).

    A co-simulation adds its work at the two ends of a scan (:mod:`plcsim.sim.stepping`): ``before`` is called
    once the scan is sure to run, before the input image is read (the wiring's copy of the sensors); ``after``
    is called at the scan's end in place of the :attr:`~plcsim.controllers.s7.cpu.CPU.scan_end` subscriber
    ``replaces`` while that is the one subscribed (the recorder's row, written without a call through the CPU).
    With ``fills`` the scan runs only when it ends exactly at ``until_ns`` (a host's step it fills, so that nothing
    else is due in the step unless the scan stopped the CPU); a host holds it from step to step, so it declines
    once another program was downloaded (the CPU's own is built again with each download)."""
    plan = cpu._cyclic_plan
    fixed, whole, aliased_inputs = plan
    if not cpu.config.fuse or not fixed or whole is None or aliased_inputs:
        return None
    clock, ticks, t, inputs = cpu.clock, cpu._ticks, cpu.t, cpu.inputs
    d = t.__dict__
    refresh, snapshot = d.update, inputs.copy  # the input image's two copies, bound once
    out_getter, output_names = cpu._out_getter, cpu.output_names
    scan_end = cpu.scan_end
    latch, after_exception, push_scan = cpu._latch_clock_memory, cpu._after_exception, cpu._push_scan
    stack = cpu._stack
    interrupts = bool(cpu._interrupts)  # (the program's: the same until the next download)

    def scan(until_ns: int) -> bool:
        t0 = cpu._ob1_next
        now = clock.now
        if t0 < now:
            t0 = now
        end = t0 + fixed
        if (end != until_ns if fills else end > until_ns) or cpu.forces or stack or cpu.mode != RUN:
            return False  # ends after the host's step (or not at it), something is forced, a scan is unfinished
            # or the CPU in STOP
        if (interrupts and end > cpu._next_irq) or (fills and cpu._cyclic_plan is not plan):
            return False  # an interrupt falls inside; another program was downloaded since the host built this
        if before is not None:
            before(inputs, t0)
        # -- the start (TaskRunner._begin_scan) --
        clock.now = t0
        ticks[0] = 0
        if t0 >= cpu._clock_next:
            latch(t0)
        refresh(inputs)
        cpu.image_in = snapshot()
        cpu.scan_start_ns = t0
        # -- the networks --
        try:
            whole(t)
        except KeyboardInterrupt:
            raise
        except BaseException as exc:  # noqa: BLE001 - sorted out by the general handler
            ex = push_scan(t0, fixed)
            after_exception(ex, exc, NEVER)  # nothing is due before the end: the same as up to the interrupt
            if cpu.mode != RUN:
                return True
            stack.pop()
        # -- the end (TaskRunner._end_scan; nothing can force a tag while the program runs) --
        if end > clock.now:
            clock.now = end
        values = out_getter(d)
        if values != cpu._last_out:
            cpu._last_out = values
            cpu.outputs.update(zip(output_names, values))
            cpu.output_version += 1
        cpu._ob1_next = cpu.scan_end_ns = end
        cpu.scan_count += 1
        call = scan_end.call
        if call is not None:
            if call is replaces:
                after(t0, end)  # type: ignore[misc]
            else:
                call(cpu)
        if cpu._first_scan or cpu._diag_changed:
            cpu._first_scan = cpu._diag_changed = False
            cpu._set_system_bits()
        return True

    return scan
