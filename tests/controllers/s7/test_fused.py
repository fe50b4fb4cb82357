"""Issue 29: one OB1 scan in one call (:mod:`plcsim.controllers.s7.fused`) against the general scan loop, on
random programs (hypothesis).

Random programs of the subset (seal-ins, set/reset coils, TON/TOF with their refresh on read, a CTU,
-|P|- contacts, INT arithmetic that wraps, a division that may fail, a JMP over a network, the clock and
system memory bits, now and then an OB30 that pre-empts OB1 between its networks) run three ways: fused
(the default), in the cyclic loop unfused, and in the general pre-emptive loop unfused. The host drives them
by whole scans or by steps that end inside a scan, and sometimes forces a tag. Every trace row, the CPU's
mode, its diagnostics (a STOP names the network and the line), its scan count, clock and outputs must agree.
"""

from __future__ import annotations

import hypothesis.strategies as st
from hypothesis import given, settings

from plcsim import CPU, Int, Tag
from plcsim.controllers.s7.fused import fused_scan
from plcsim.sim.recorder import Recorder

INPUTS = [f"I{k}" for k in range(4)]
OUTPUTS = [f"Q{k}" for k in range(4)]
WORDS = ["M0", "M1"]
SCANS = 80


def _tags() -> dict[str, Tag]:
    table = {name: Tag(f"%I0.{k}") for k, name in enumerate(INPUTS)}
    table.update({name: Tag(f"%Q0.{k}") for k, name in enumerate(OUTPUTS)})
    table.update({name: Tag(f"%MW{10 + 2 * k}", Int) for k, name in enumerate(WORDS)})
    return table


def _bool_expr(depth: int = 2) -> st.SearchStrategy[str]:
    leaves = st.one_of(
        st.sampled_from([f"t.{n}" for n in INPUTS + OUTPUTS] + ["t.Clock_10Hz", "t.FirstScan"]),
        st.sampled_from(["t.T0.Q", "t.T1.Q", "t.C0.QU"]),
        st.builds(
            lambda w, op, n: f"t.{w} {op} {n}",
            st.sampled_from(WORDS),
            st.sampled_from(["<", ">="]),
            st.integers(-5, 40),
        ),
    )
    if depth == 0:
        return leaves
    inner = _bool_expr(depth - 1)
    return st.one_of(
        leaves,
        st.builds(lambda a: f"not ({a})", inner),
        st.builds(lambda a, op, b: f"({a}) {op} ({b})", inner, st.sampled_from(["and", "or"]), inner),
    )


def _statement() -> st.SearchStrategy[list[str]]:
    q, w, tm = st.sampled_from(OUTPUTS), st.sampled_from(WORDS), st.sampled_from(["T0", "T1"])
    b = _bool_expr()
    ms = st.integers(1, 9).map(lambda n: f'"{n}ms"')
    return st.one_of(
        st.builds(lambda q, x: [f"t.{q} = {x}"], q, b),
        st.builds(lambda x, q, v: [f"if {x}:", f"    t.{q} = {v}"], b, q, st.booleans()),
        st.builds(
            lambda tm, box, x, pt: [f"t.{tm}.{box}(IN={x}, PT={pt})"], tm, st.sampled_from(["TON", "TOF"]), b, ms
        ),
        st.builds(lambda w, tm: [f"t.{w} = t.{tm}.ET"], w, tm),
        st.builds(lambda x, r, q: [f"if t.C0.CTU(CU={x}, R={r}, PV=3):", f"    t.{q} = True"], b, b, q),
        st.builds(lambda x, w: [f'if P({x}, "E0"):', f"    t.{w} = t.{w} * 300 + 7"], b, w),
        st.builds(lambda w, v, n: [f"t.{w} = t.{v} + {n}"], w, st.sampled_from(WORDS), st.integers(-3, 30_000)),
        st.builds(lambda w, v: [f"t.{w} = 1000 // (t.{v} % 9)"], w, st.sampled_from(WORDS)),
        st.builds(lambda x: [f"if {x}:", '    JMP("last")'], b),
    )


@st.composite
def programs(draw: st.DrawFn) -> str:
    lines = ["T0 = IEC_TIMER()", "T1 = IEC_TIMER()", "C0 = IEC_COUNTER()", "E0 = Bool()"]
    names = []
    count = draw(st.integers(2, 5))
    for k in range(count):
        names.append(f"n{k}")
        lines += ["", ""] + (['@label("last")'] if k == count - 1 else []) + [f"def n{k}(t):"]
        for statement in draw(st.lists(_statement(), min_size=1, max_size=3)):
            lines += [f"    {line}" for line in statement]
    lines += ["", "", f"OB1 = [{', '.join(names)}]", ""]
    if draw(st.booleans()):  # an OB30 that pre-empts OB1 between networks
        period = draw(st.sampled_from(["3ms", "7ms", "10ms"]))
        body = draw(st.lists(_statement().filter(lambda s: "JMP" not in s[-1]), min_size=1, max_size=2))
        lines += ["def irq(t):", *(f"    {line}" for s in body for line in s)]
        lines += ["", f'OB30 = CyclicInterrupt(irq, period="{period}")', ""]
    return "\n".join(lines)


def _run(source: str, schedule: list[dict[str, bool]], step_ns: int | None, force: bool, loop: str) -> tuple:
    cpu = CPU(
        tags=_tags(),
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
    source=programs(),
    schedule=st.lists(st.fixed_dictionaries({n: st.booleans() for n in INPUTS}), min_size=SCANS, max_size=SCANS),
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
