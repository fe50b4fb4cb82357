"""The whole cycle of a program of P0 alone as one generated call (``head``, see ``tecomat.fused.fuse``) and the
general path (the plain closures, the turnaround, the process plan and the cycle's end as methods) compute the
same controller: random straight programs of the generated subset, driven through the wiring's dict, the terminals,
``scan`` and ``run_until`` (whole cycles and cycles split across calls), with interrupts, restarts and power cuts
between them, leave the same scratchpad, stacks, block state, outputs, symbols and clock after every step."""

from __future__ import annotations

from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from test_tecomat_fast_equivalence import _instructions, _state

from benchmarks.tecomat import new_controller
from plcsim.controllers.tecomat.cpu import TecomatCPU

SYMBOLS = "#def IN0 x0.0\n#def IN3 x0.3\n#def INB x1\n#def OUT y0.1\n#def OUTW yw0\n#def CNT rw10\n"
ALIAS = "#def ALL x0\n"
"""A name on the same terminals as IN0 and IN3: the turnaround samples such inputs another way."""


@st.composite
def programs(draw) -> str:
    """A straight program (no jump, label or call): P0 is one run, so it gets a head."""
    lines = ["#table byte tab = 3, 15, 30, 65, 137, 240"]
    lines += draw(st.lists(_instructions(), min_size=1, max_size=30))
    return SYMBOLS + (ALIAS if draw(st.booleans()) else "") + "\n".join(lines) + "\n"


def _seen(cpu: TecomatCPU) -> tuple:
    return (
        _state(cpu),
        dict(cpu.outputs),
        cpu.output_version,
        dict(vars(cpu.t)),
        dict(cpu.image_in),
        cpu.scan_count,
        cpu.clock.now,
        cpu.next_event_ns(),
        cpu.scan_start_ns,
        cpu.scan_end_ns,
    )


steps = st.one_of(
    st.tuples(st.just("input"), st.sampled_from(["IN0", "IN3", "INB", "ALL"]), st.integers(0, 255)),
    st.tuples(st.just("terminal"), st.sampled_from(["X0", "X1", "X0.3"]), st.integers(0, 255)),
    st.tuples(st.just("scan"), st.integers(1, 4)),
    st.tuples(st.just("run"), st.integers(1, 30_000_000)),
    st.tuples(st.just("event"), st.integers(1, 8)),
    st.sampled_from([("restart",), ("power",), ("write",)]),
)


def _apply(cpu: TecomatCPU, step: tuple) -> None:
    kind = step[0]
    if kind == "input" and step[1] in cpu.inputs:
        cpu.inputs[step[1]] = step[2] if step[1] in ("INB", "ALL") else bool(step[2] & 1)
    elif kind == "terminal":
        cpu.set_input(step[1], step[2] & (1 if "." in step[1] else 255))
    elif kind == "scan":
        cpu.scan(step[1])
    elif kind == "run":
        cpu.run(step[1])
    elif kind == "event":
        cpu.raise_event(step[1])
    elif kind == "restart":
        cpu.stop()
        cpu.start()
    elif kind == "power":
        cpu.power_cycle()
    elif kind == "write":
        cpu.write("CNT", cpu.peek("CNT") + 3 & 0xFFFF)


@settings(max_examples=300, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(
    program=programs(),
    steps=st.lists(steps, min_size=1, max_size=25),
    subscribed=st.booleans(),
    options=st.fixed_dictionaries(
        {
            "cycle": st.sampled_from(["1ms", "7ms", "15ms"]),
            "clear_all_stacks": st.booleans(),
            "pop_fill_keeps_a7": st.booleans(),
            "timer_ticks": st.sampled_from(["per_timer", "global"]),
        }
    ),
)
def test_the_whole_cycle_in_one_call_and_the_general_path_run_the_same(program, steps, subscribed, options):
    head, plain = TecomatCPU(program, **options), TecomatCPU(program, fuse=False, **options)
    assert head._head is not None and plain._head is None
    rows: dict[TecomatCPU, list] = {head: [], plain: []}
    if subscribed:  # a recorder reads the symbols at every cycle's end
        for cpu in (head, plain):
            cpu.on_scan_end = lambda c: rows[c].append((c.scan_end_ns, dict(vars(c.t)), dict(c.outputs)))
    for step in [("scan", 1), *steps]:
        for cpu in (head, plain):
            _apply(cpu, step)
        assert _seen(head) == _seen(plain), (program, step)
        assert rows[head] == rows[plain], (program, step)


def test_a_program_with_a_jump_or_another_process_keeps_the_general_path():
    straight = TecomatCPU("LD X0.0\nWR Y0.0\n")
    jumping = TecomatCPU("LD X0.0\nJMC L1\nLD 1\nWR Y1\nL 1\nLD X0.0\nWR Y0.0\n")
    periodic = TecomatCPU("P 0\nLD X0.0\nWR Y0.0\nE 0\nP 5\nLD X0.1\nWR Y0.1\nE 5\n")
    assert straight._head is not None and new_controller()._head is not None  # (what the benchmark times)
    assert jumping._head is None and periodic._head is None
