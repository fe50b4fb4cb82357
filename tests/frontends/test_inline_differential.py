"""Whole-task code generation against the networks one by one, on random programs (hypothesis).

A task's merged function has its timers, counters and edge contacts written out
(:mod:`plcsim.frontends.python.inline`). Random programs of the subset (seal-ins, set/reset coils, TON, TOF,
their Q and ET read after the box or after a write of PT, CTU, -|P|- and -|N|- on memory bits, INT
arithmetic that wraps, a division that may fail) run three ways:
network by network (no merge, the reference), merged without and merged with the boxes written out. Every
trace row, the CPU's mode and its diagnostics (a STOP names the network and the line) must agree.
"""

from __future__ import annotations

import hypothesis.strategies as st
import pytest
from hypothesis import HealthCheck, given, settings

import plcsim.frontends.python.pipeline
from plcsim import CPU, Int, Tag
from plcsim.sim.recorder import Recorder

INPUTS = [f"I{k}" for k in range(4)]
OUTPUTS = [f"Q{k}" for k in range(4)]
WORDS = ["M0", "M1"]
TIMERS = ["T0", "T1"]
EDGES = ["E0", "E1", "E2"]
SCANS = 120


def _tags() -> dict[str, Tag]:
    table = {name: Tag(f"%I0.{k}") for k, name in enumerate(INPUTS)}
    table.update({name: Tag(f"%Q0.{k}") for k, name in enumerate(OUTPUTS)})
    table.update({name: Tag(f"%MW{10 + 2 * k}", Int) for k, name in enumerate(WORDS)})
    return table


def _bool_expr(depth: int = 2) -> st.SearchStrategy[str]:
    leaves = st.one_of(
        st.sampled_from([f"t.{n}" for n in INPUTS + OUTPUTS]),
        st.sampled_from([f"t.{n}.Q" for n in TIMERS] + ["t.C0.QU"]),
        st.builds(
            lambda w, op, n: f"t.{w} {op} {n}",
            st.sampled_from(WORDS),
            st.sampled_from(["<", ">=", "!="]),
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
    q, w, e, tm = (st.sampled_from(x) for x in (OUTPUTS, WORDS, EDGES, TIMERS))
    b = _bool_expr()
    ms = st.integers(1, 12).map(lambda n: f'"{n}ms"')
    return st.one_of(
        st.builds(lambda q, x: [f"t.{q} = {x}"], q, b),
        st.builds(lambda x, q, v: [f"if {x}:", f"    t.{q} = {v}"], b, q, st.booleans()),
        st.builds(
            lambda tm, box, x, pt: [f"t.{tm}.{box}(IN={x}, PT={pt})"], tm, st.sampled_from(["TON", "TOF"]), b, ms
        ),
        st.builds(lambda tm, x, pt, q: [f"if t.{tm}.TON(IN={x}, PT={pt}):", f"    t.{q} = not t.{q}"], tm, b, ms, q),
        st.builds(lambda w, tm: [f"t.{w} = t.{tm}.ET"], w, tm),
        st.builds(lambda tm, pt: [f"t.{tm}.PT = {pt}"], tm, ms),  # a read after it refreshes with this PT
        st.builds(
            lambda x, r, pv, q: [f"if t.C0.CTU(CU={x}, R={r}, PV={pv}):", f"    t.{q} = True"],
            b,
            b,
            st.integers(1, 4),
            q,
        ),
        st.builds(lambda x, r: [f"t.C0.CTU(R={r}, CU={x}, PV=3)"], b, b),
        st.builds(lambda x, e, w: [f"if P({x}, {e!r}):", f"    t.{w} = t.{w} * 300 + 7"], b, e, w),
        st.builds(lambda x, e, q: [f"edge = N({x}, {e!r})", f"t.{q} = edge"], b, e, q),
        st.builds(lambda w, v, n: [f"t.{w} = t.{v} + {n}"], w, st.sampled_from(WORDS), st.integers(-3, 30_000)),
        st.builds(lambda w, v: [f"t.{w} = 1000 // (t.{v} % 7)"], w, st.sampled_from(WORDS)),
    )


@st.composite
def programs(draw: st.DrawFn) -> str:
    lines = [f"{name} = IEC_TIMER()" for name in TIMERS] + ["C0 = IEC_COUNTER()"]
    lines += [f"{name} = Bool()" for name in EDGES]
    names = []
    for k in range(draw(st.integers(2, 5))):
        names.append(f"n{k}")
        lines += ["", "", f"def n{k}(t):"]
        for statement in draw(st.lists(_statement(), min_size=1, max_size=3)):
            lines += [f"    {line}" for line in statement]
    lines += ["", "", f"OB1 = [{', '.join(names)}]", ""]
    return "\n".join(lines)


def _run(source: str, schedule: list[dict[str, bool]]) -> tuple:
    cpu = CPU(tags=_tags(), program=source, textbook_strict_timers=False)
    recorder = Recorder(cpu)
    recorder.attach()
    for changes in schedule:
        cpu.inputs.update(changes)
        cpu.scan()
        if cpu.mode != "RUN":
            break
    return recorder.trace.digest(), cpu.mode, [(d.event, d.message) for d in cpu.diagnostics], cpu.scan_count


@pytest.fixture
def three_ways(monkeypatch: pytest.MonkeyPatch):
    pipeline = plcsim.frontends.python.pipeline

    def run(source: str, schedule: list[dict[str, bool]]) -> list[tuple]:
        results = []
        for merged, inline in ((False, False), (True, False), (True, True)):
            monkeypatch.setattr(pipeline, "MAX_MERGED_STATEMENTS", 5000 if merged else 0)
            monkeypatch.setattr(pipeline, "INLINE_BOXES", inline)
            results.append(_run(source, schedule))
        return results

    return run


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(
    source=programs(),
    schedule=st.lists(st.fixed_dictionaries({n: st.booleans() for n in INPUTS}), min_size=SCANS, max_size=SCANS),
)
def test_boxes_written_out_run_as_the_networks_one_by_one(three_ways, source: str, schedule: list) -> None:
    by_network, merged, written_out = three_ways(source, schedule)
    assert merged == by_network, source
    assert written_out == by_network, source


def test_the_workload_has_its_boxes_written_out():
    """The 25-network workload: no box call is left in OB1's merged function (the fast path is taken)."""
    import dis

    from benchmarks import workload

    ops = list(dis.get_instructions(workload.new_cpu()._ob1.merged))
    loaded = {i.argval for i in ops if i.opname in ("LOAD_METHOD", "LOAD_ATTR", "LOAD_GLOBAL")}
    assert not loaded & {"TON", "TOF", "CTU", "P"}
    assert {"_inert", "_running", "CU", "CV"} <= loaded


PT_WRITTEN_BETWEEN = """
T0 = IEC_TIMER()
T1 = IEC_TIMER()


def shorten(t):
    t.T1.PT = "2ms"


def n0(t):
    t.T0.TON(IN=t.I0, PT="9ms")
    t.Q0 = t.T0.Q
    t.T0.PT = "3ms"
    t.Q1 = t.T0.Q


def n1(t):
    t.T1.TON(IN=t.I1, PT="9ms")
    shorten(t)
    t.Q2 = t.T1.Q
    t.M0 = t.T1.ET


OB1 = [n0, n1]
"""


def test_a_timer_read_after_a_write_of_its_pt_refreshes_with_that_pt(three_ways):
    """A read right after its box takes Q and ET as the box stored them; after a write of PT (in the network or
    in a function it calls) the read refreshes with the new PT, as the networks one by one do."""
    by_network, merged, written_out = three_ways(PT_WRITTEN_BETWEEN, [{"I0": True, "I1": True}] * 12)
    assert merged == by_network
    assert written_out == by_network
