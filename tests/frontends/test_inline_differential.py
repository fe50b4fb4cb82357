"""Whole-task code generation against the networks one by one, on random programs (hypothesis).

A task's merged function has its timers, counters and edge contacts written out
(:mod:`plcsim.frontends.python.inline`, without the Bool checks of operands the typing proves Bool) and keeps
the tags it reads often in locals (:mod:`plcsim.frontends.python.localize`). Random programs of the subset
(tests/random_programs.py: seal-ins, set/reset coils, TON, TOF, their Q and ET read after the box or after a
write of PT, CTU, -|P|- and -|N|- on memory bits, INT arithmetic that wraps, a division that may fail; calls
of the program's functions and of MOVE, loops, stores and boxes that refuse an INT) run four ways: network by
network (no merge, the reference), merged, merged with the boxes written out, and that with tags as locals.
Every trace row, the CPU's mode, its diagnostics (a STOP names the network and the line) and the tags' values
at the end (after a STOP: as the fault left them) must agree.
"""

from __future__ import annotations

import pytest
from hypothesis import HealthCheck, given, settings
from random_programs import HELPERS, Vocabulary, programs, schedules, tags

import plcsim.frontends.python.pipeline
from plcsim import CPU, Tag
from plcsim.sim.recorder import Recorder

SCANS = 120
VOCABULARY = Vocabulary(compare=("<", ">=", "!="), edges=("E0", "E1", "E2"), max_ms=12, modulus=7, more_boxes=True)
CALLS = Vocabulary(compare=("<", ">=", "!="), edges=("E0", "E1"), modulus=7, more_boxes=True, calls=True)
BLOCKS = Vocabulary(compare=("<", ">=", "!="), edges=("E0",), modulus=7, more_boxes=True, blocks=True)
WAYS = {
    "by network": (False, False, False),
    "merged": (True, False, False),
    "boxes written out": (True, True, False),
    "tags as locals": (True, True, True),
}
"""How a program runs: merged into one function, its boxes written out, its tags in locals (pipeline flags)."""


def _run(source: str, schedule: list[dict[str, bool]], tags: dict[str, Tag]) -> tuple:
    cpu = CPU(tags=tags, program=source, textbook_strict_timers=False, watchdog_iterations=300)
    recorder = Recorder(cpu)
    recorder.attach()
    for changes in schedule:
        cpu.inputs.update(changes)
        cpu.scan()
        if cpu.mode != "RUN":
            break
    values = {k: v for k, v in cpu.t.__dict__.items() if isinstance(v, bool | int | float | str)}
    if "D" in cpu.t.__dict__:  # the data block of the vocabulary's ``blocks`` (a NaN compared by its repr)
        values.update({f"D.{k}": repr(v) for k, v in cpu.t.D.__dict__.items()})
    diagnostics = [(d.event, d.message, d.network, d.line) for d in cpu.diagnostics]
    return recorder.trace.digest(), cpu.mode, diagnostics, cpu.scan_count, values


@pytest.fixture
def ways(monkeypatch: pytest.MonkeyPatch):
    """Run a program each of the :data:`WAYS`; the results by way."""
    pipeline = plcsim.frontends.python.pipeline

    def run(source: str, schedule: list[dict[str, bool]], table: dict[str, Tag] | None = None) -> dict[str, tuple]:
        results = {}
        for way, (merged, inline, local) in WAYS.items():
            monkeypatch.setattr(pipeline, "MAX_MERGED_STATEMENTS", 5000 if merged else 0)
            monkeypatch.setattr(pipeline, "INLINE_BOXES", inline)
            monkeypatch.setattr(pipeline, "LOCAL_TAGS", local)
            results[way] = _run(source, schedule, table or tags())
        return results

    return run


def _all_alike(results: dict[str, tuple], source: str) -> None:
    reference = results["by network"]
    for way, result in results.items():
        assert result == reference, f"{way}:\n{source}"


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(source=programs(VOCABULARY), schedule=schedules(SCANS))
def test_boxes_written_out_run_as_the_networks_one_by_one(ways, source: str, schedule: list) -> None:
    _all_alike(ways(source, schedule), source)


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(source=programs(CALLS), schedule=schedules(SCANS))
def test_tags_as_locals_run_as_the_networks_one_by_one(ways, source: str, schedule: list) -> None:
    """With calls of the program's functions and of MOVE between the runs a merged function keeps its tags in
    locals for, loops, and faults in the middle of a task (a division by zero, an INT stored into a BOOL, the
    watchdog): the same rows, diagnostics and tag values at the end (at a STOP, the tags as the fault left
    them)."""
    _all_alike(ways(source, schedule), source)


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture])
@given(source=programs(BLOCKS), schedule=schedules(SCANS))
def test_data_block_members_run_as_the_networks_one_by_one(ways, source: str, schedule: list) -> None:
    """Edge contacts on a data block's bits written out, its member dict kept in a local, its REAL stores rounded
    in the generated code (constants converted at load), up to a NaN or an infinity stored into an INT."""
    _all_alike(ways(source, schedule), source)


def test_the_workload_has_its_boxes_written_out():
    """The 25-network workload: no box call is left in OB1's merged function (the fast path is taken)."""
    import dis

    from benchmarks import workload

    ops = list(dis.get_instructions(workload.new_cpu()._ob1.merged))
    loaded = {i.argval for i in ops if i.opname in ("LOAD_METHOD", "LOAD_ATTR", "LOAD_GLOBAL")}
    assert not loaded & {"TON", "TOF", "CTU", "P"}
    assert {"_inert", "_running", "CU", "CV"} <= loaded
    assert not loaded & {"_box_bool", "_bools", "_edge_bool"}  # every operand is a Bool the typing knows


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


def test_a_timer_read_after_a_write_of_its_pt_refreshes_with_that_pt(ways):
    """A read right after its box takes Q and ET as the box stored them; after a write of PT (in the network or
    in a function it calls) the read refreshes with the new PT, as the networks one by one do."""
    _all_alike(ways(PT_WRITTEN_BETWEEN, [{"I0": True, "I1": True}] * 12), PT_WRITTEN_BETWEEN)


CALL_BETWEEN = (
    HELPERS
    + """

def n0(t):
    t.M1 = t.M0 * 3 + t.M0
    t.Q0 = t.M0 > 2 and t.M0 < 9


def n1(t):
    bump(t)
    t.Q1 = t.M0 > 4 and t.M0 != 7 and t.M0 < 100


def n2(t):
    t.M1 = t.M1 + t.M0 * 2 + t.M0
    t.Q2 = 10 // (t.M0 - 12) > 0


OB1 = [n0, n1, n2]
"""
)


def _merged_code(source: str, table: dict[str, Tag]):
    return CPU(tags=table, program=source)._ob1.merged.__code__


def test_a_call_between_two_runs_has_the_run_after_it_read_its_tags_again(ways):
    """``bump(t)`` changes M0, which the statements before and after it keep in a local: after the call they
    read it from the tags again. On the 12th scan the division fails in the middle of OB1; the tags are then
    as the statements before the fault stored them, the same each way."""
    assert {"_tag_M0"} <= set(_merged_code(CALL_BETWEEN, tags()).co_varnames)
    results = ways(CALL_BETWEEN, [{}] * 20)
    _all_alike(results, CALL_BETWEEN)
    _, mode, diagnostics, _, values = results["tags as locals"]
    assert mode == "STOP" and values["M0"] == 12 and values["M1"] == 4 * 11 + 3 * 12  # n2 stored M1, then failed
    assert any("network 3 (n2)" in message and "ZeroDivisionError" in message for _, message, _, _ in diagnostics)


WRAPS = """
def n0(t):
    t.M0 = t.M0 + 20000
    t.M1 = t.M0 - t.M1


def n1(t):
    t.Q0 = t.M0 < 0 and t.M1 > t.M0
    t.M1 = t.M1 * 3 + t.M0
    t.Q1 = t.M1 > 0 or t.M1 < -100 or t.M1 == 7


OB1 = [n0, n1]
"""


def test_int_stores_in_locals_wrap_as_stores_into_the_tags(ways):
    """An INT kept in a local takes the wrapped value its store converted, not the sum Python computed."""
    assert {"_tag_M0", "_tag_M1"} <= set(_merged_code(WRAPS, tags()).co_varnames)
    results = ways(WRAPS, [{}] * 30)
    _all_alike(results, WRAPS)
    assert -32768 <= results["tags as locals"][4]["M1"] <= 32767
