"""Issue 11: the scan loop without interrupts (``_run_cyclic``, the hot path) writes out ``_begin_scan`` and
``_end_scan`` rather than calling them (a measured 3 % of the PLC-only rate, see its docstring); issue 29:
a scan nothing can interrupt runs in one call (:mod:`plcsim.controllers.s7.fused`). These tests run the
same programs through them and through the general pre-emptive loop unfused and ask for the same trace bit
for bit, so that the written-out copies cannot drift from the methods the general loop calls."""

from __future__ import annotations

import pytest

from benchmarks import workload
from plcsim import CPU, Int, Tag
from plcsim.sim.recorder import Recorder

COUNTER = """
def n1(t):
    t.LED = t.TL and not t.STOP
    if P(t.TL, "EDGE"):
        t.COUNT += 1

def n2(t):
    t.FAST = t.Clock_10Hz and not t.FirstScan
    t.WORD = t.IN_WORD + t.COUNT
    if t.COUNT == 7:
        t.WORD = 100 // t.ZERO

OB1 = [n1, n2]
"""
TAGS = {
    "TL": Tag("%I0.0"),
    "STOP": Tag("%I0.1"),
    "IN_WORD": Tag("%IW2", Int),
    "IN_LOW": Tag("%I3.0"),  # overlaps %IW2: the inputs alias, the image is refreshed tag by tag
    "LED": Tag("%Q0.0"),
    "FAST": Tag("%Q0.1"),
    "EDGE": Tag("%M0.0"),
    "COUNT": Tag("%MW10", Int),
    "WORD": Tag("%MW12", Int),
    "ZERO": Tag("%MW14", Int),
}


def unfused(cpu: CPU, general: bool = True) -> CPU:
    """``cpu`` with every scan in a loop: the general one (``general``), or the cyclic one."""
    cpu.config.fuse = False
    cpu._plan_cyclic()
    if general:
        cpu._run_cyclic = cpu._run_preemptive  # the loop a program with interrupts runs in
    return cpu


def run(make_cpu, schedule, general: bool, step_ns: int | None = None, fuse: bool = True) -> tuple[str, int, str]:
    cpu = make_cpu()
    if general or not fuse:
        unfused(cpu, general)
    recorder = Recorder(cpu)
    recorder.attach()
    for changes in schedule:
        if changes:
            cpu.inputs.update(changes)
        if step_ns is None:
            cpu.scan()
        else:
            cpu.run_until(cpu.now + step_ns)
    return recorder.trace.digest(), cpu.scan_count, cpu.mode


def test_the_workload_runs_alike_in_both_loops():
    schedule = workload.build_schedule(3000)
    fused = run(workload.new_cpu, schedule, general=False)
    assert fused == run(workload.new_cpu, schedule, general=False, fuse=False)
    assert fused == run(workload.new_cpu, schedule, general=True)


@pytest.mark.parametrize("step_ns", [None, 700_000, 2_500_000], ids=["scan", "0.7ms steps", "2.5ms steps"])
@pytest.mark.parametrize(
    "options",
    [
        {},
        {"jitter": "300us", "seed": 4},
        {"network_cost": "400us", "min_cycle": "1ms"},
    ],
    ids=["fixed cycle", "jitter", "network cost"],
)
def test_aliased_inputs_forces_clock_and_system_memory_and_a_fault_run_alike_in_both_loops(options, step_ns):
    schedule = [{"TL": k % 6 < 3, "STOP": k % 50 == 49, "IN_WORD": k} for k in range(200)]

    def make_cpu() -> CPU:
        cpu = CPU(tags=TAGS, program=COUNTER, clock_memory_byte=20, system_memory_byte=21, **options)
        cpu.forces["STOP"] = False
        return cpu

    fast = run(make_cpu, schedule, general=False, step_ns=step_ns)
    assert fast == run(make_cpu, schedule, general=True, step_ns=step_ns)
    assert fast[2] == "STOP"  # the seventh rising edge of TL divides by zero: both loops stop alike


JUMPING = """
def n1(t):
    t.LED = t.TL
    if t.STOP:
        JMP("last")

def n2(t):
    t.COUNT += 1
    if t.COUNT == 40:
        t.WORD = 100 // t.ZERO

@label("last")
def n3(t):
    t.WORD = t.IN_WORD + t.COUNT

OB1 = [n1, n2, n3]
"""


@pytest.mark.parametrize("step_ns", [None, 700_000, 1_000_000, 2_500_000], ids=["scan", "0.7ms", "1ms", "2.5ms"])
@pytest.mark.parametrize(
    "options",
    [{}, {"jitter": "300us", "seed": 4}, {"cycle": "3ms"}, {"network_cost": "400us", "min_cycle": "1ms"}],
    ids=["fixed cycle", "jitter", "3ms cycle", "network cost"],
)
def test_a_scan_off_the_stack_runs_alike_in_both_loops(options, step_ns):
    """No forces, no aliased inputs: the whole program runs in one call and a scan that ends within the step
    never goes on the stack; one that jumps (continued network by network), one that ends after the step
    (its end in a later call) and one that faults do."""
    tags = {name: tag for name, tag in TAGS.items() if name != "IN_LOW"}
    schedule = [{"TL": k % 6 < 3, "STOP": k % 10 == 9, "IN_WORD": k} for k in range(400)]

    def make_cpu() -> CPU:
        return CPU(tags=tags, program=JUMPING, clock_memory_byte=20, system_memory_byte=21, **options)

    fast = run(make_cpu, schedule, general=False, step_ns=step_ns)
    assert fast == run(make_cpu, schedule, general=False, step_ns=step_ns, fuse=False)
    assert fast == run(make_cpu, schedule, general=True, step_ns=step_ns)
    assert fast[2] == "STOP"  # the 40th scan that ran n2 divided by zero, in both loops


def _hooked_run(general: bool) -> tuple[str, int, list[str], int]:
    """A run in 1 ms steps whose scan-end subscriber fails once (at scan 30), downloads a new program at scan 60
    and, at scan 90, runs the CPU on for 3 ms from inside the hook (a call of the loop while it runs)."""
    tags = {name: tag for name, tag in TAGS.items() if name != "IN_LOW"}
    cpu = CPU(tags=tags, program=JUMPING.replace("== 40", "== 4000"))
    if general:
        unfused(cpu)
    recorder = Recorder(cpu)
    recorder.attach()
    seen: list[str] = []

    def hook(cpu: CPU) -> None:
        if cpu.scan_count == 30:
            raise RuntimeError("a subscriber's bug")
        if cpu.scan_count == 60:
            cpu.load(JUMPING.replace("== 40", "== 4000").replace("COUNT += 1", "COUNT += 2"))
            cpu.start()
        if cpu.scan_count == 90:
            cpu.run_until(cpu.now + 3_000_000)
        seen.append(f"{cpu.scan_count}@{cpu.now}")

    cpu.scan_end.add(hook)
    failures = 0
    for k in range(150):
        cpu.inputs.update({"TL": k % 6 < 3, "IN_WORD": k})
        try:
            cpu.run_until(cpu.now + 1_000_000)
        except RuntimeError:
            failures += 1
    return recorder.trace.digest(), cpu.scan_count, seen, failures


def test_the_kept_loop_survives_a_failing_subscriber_a_download_and_a_nested_call():
    """The cyclic loop is a generator kept between calls (made at each download): a subscriber's exception ends
    it (the next call makes a new one), a download in the middle of a run replaces it, and a call from inside a
    subscriber gets a loop of its own; the scans, their times and the trace are those of the general loop."""
    fast = _hooked_run(general=False)
    assert fast == _hooked_run(general=True)
    assert fast[3] == 1
    assert "30@30000000" not in fast[2] and fast[2].count("93@93000000") == 2  # the nested call ran scans 91-93
    assert fast[1] == 153
