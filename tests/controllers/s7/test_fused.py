"""Issue 29: one OB1 scan in one call (:mod:`plcsim.controllers.s7.fused`) against the general scan loop, on
random programs (hypothesis).

Random programs of the subset (tests/random_programs.py: seal-ins, set/reset coils, TON/TOF with their refresh
on read, a CTU, -|P|- contacts, INT arithmetic that wraps, a division that may fail, a JMP over a network, the
clock and system memory bits, now and then an OB30 that pre-empts OB1 between its networks) run three ways: fused
(the default), in the cyclic loop unfused, and in the general pre-emptive loop unfused. The host drives them
by whole scans or by steps that end inside a scan, and sometimes forces a tag. Every trace row, the CPU's
mode, its diagnostics (a STOP names the network and the line), its scan count, clock and outputs must agree.
"""

from __future__ import annotations

import hypothesis.strategies as st
from hypothesis import given, settings
from random_programs import Vocabulary, programs, schedules, tags

from plcsim import CPU, Tag
from plcsim.controllers.s7.fused import fused_scan
from plcsim.sim.recorder import Recorder

SCANS = 80
VOCABULARY = Vocabulary(leaves=("t.Clock_10Hz", "t.FirstScan"), jumps=True, interrupt=True)


def _run(source: str, schedule: list[dict[str, bool]], step_ns: int | None, force: bool, loop: str) -> tuple:
    cpu = CPU(
        tags=tags(),
        program=source,
        textbook_strict_timers=False,
        clock_memory_byte=20,
        system_memory_byte=21,
        fuse=loop == "fused",
    )
    if loop == "general":
        cpu._run_cyclic = cpu._run_preemptive  # type: ignore[method-assign]
    recorder = Recorder(cpu)
    recorder.attach()
    for k, changes in enumerate(schedule):
        cpu.inputs.update(changes)
        if force and k == SCANS // 3:
            cpu.forces["Q1"] = True
        if force and k == SCANS // 2:
            cpu.forces.clear()
        if step_ns is None:
            cpu.scan()
        else:
            cpu.run_until(cpu.now + step_ns)
        if cpu.mode != "RUN":
            break
    return (
        recorder.trace.digest(),
        cpu.mode,
        [(d.event, d.message, d.network, d.line) for d in cpu.diagnostics],
        cpu.scan_count,
        cpu.now,
        dict(cpu.outputs),
    )


@settings(max_examples=30, deadline=None)  # 3 runs each, about 1 s an example
@given(
    source=programs(VOCABULARY),
    schedule=schedules(SCANS),
    step_ns=st.sampled_from([None, 1_000_000, 700_000, 2_500_000]),
    force=st.booleans(),
)
def test_a_fused_scan_runs_as_the_general_loop(source: str, schedule: list, step_ns: int | None, force: bool) -> None:
    fused = _run(source, schedule, step_ns, force, "fused")
    assert fused == _run(source, schedule, step_ns, force, "cyclic"), source
    assert fused == _run(source, schedule, step_ns, force, "general"), source


def test_the_workload_scans_fused():
    """The 25-network workload has a fused scan, and a CPU with ``fuse=False`` none (its tests compare the two)."""
    from benchmarks import workload

    cpu = workload.new_cpu()
    assert cpu._fused is not None
    cpu.config.fuse = False
    assert fused_scan(cpu) is None


def test_every_writer_of_an_input_reaches_the_next_fused_scan():
    """The fused scan reads the whole input image at each start, whoever wrote the terminals since the last one
    (the dict itself, :meth:`set_input`, an HMI write, ``update``) and even when nobody did: the program's own
    store into its input image does not outlive its scan, and the trace records the terminals, not that store."""
    program = "def OB1(t):\n    t.Lamp = t.Start\n    t.Start = True\n"
    cpu = CPU(tags={"Start": Tag("%I0.0"), "Lamp": Tag("%Q0.0")}, program=program)
    assert cpu._fused is not None
    recorder = Recorder(cpu)
    recorder.attach()
    writers = [
        lambda: None,  # nothing: the image still forgets the program's store
        lambda: cpu.inputs.__setitem__("Start", True),
        lambda: cpu.set_input("Start", False),
        lambda: cpu.write("Start", True),
        lambda: cpu.inputs.update({"Start": False}),
        lambda: None,
    ]
    lamps = []
    for write in [lambda: None, *writers]:
        write()
        cpu.scan()
        lamps.append(cpu.outputs["Lamp"])
    expected = [False, False, True, False, True, False, False]
    assert lamps == expected
    assert recorder.trace.column("Start").tolist() == expected


def test_a_single_output_is_written_when_it_changes_and_only_then():
    """With one output the image is compared as a pair taken in C (``tuple_getter``); every image it is compared
    with (at the download, after STOP, after an interrupt's partition) must be the same pair, or each scan would
    count a change that is none."""
    program = "def OB1(t):\n    t.Lamp = t.S\n"
    cpu = CPU(tags={"S": Tag("%I0.0"), "Lamp": Tag("%Q0.0")}, program=program)
    seen = []
    for s in [False, False, True, True]:
        cpu.set_input("S", s)
        cpu.scan()
        seen.append((cpu.outputs["Lamp"], cpu.output_version))
    cpu.stop()  # switches the lamp off: one change
    cpu.set_input("S", False)
    cpu.start()
    for _ in range(2):
        cpu.scan()
        seen.append((cpu.outputs["Lamp"], cpu.output_version))
    assert seen == [(False, 0), (False, 0), (True, 1), (True, 1), (False, 2), (False, 2)]
