"""The whole cycle of a program of P0 alone as one generated call (``head``, see ``tecomat.fused.fuse``) and the
general path (the plain closures, the turnaround, the process plan and the cycle's end as methods) compute the
same controller: random straight programs of the generated subset, driven through the wiring's dict, the terminals,
``scan`` and ``run_until`` (whole cycles and cycles split across calls), with interrupts, restarts, power cuts and
HMI writes (of outputs, input images, registers) between them, leave the same scratchpad, stacks, block state,
outputs, symbols and clock after every step.

Both paths move the I/O with the same generated lines (``symbols.sampler``, ``symbols.publisher``), so the
recorder also checks those against memory read operand by operand: at every cycle's end the outputs are what Y
holds, and the terminals hold the levels the turnaround sampled."""

from __future__ import annotations

from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from test_tecomat_fast_equivalence import _instructions, _state

from benchmarks.tecomat import new_controller
from plcsim.controllers.tecomat.cpu import TecomatCPU
from plcsim.controllers.tecomat.memory import SIZE, read

SYMBOLS = (
    "#def IN0 x0.0\n#def INB x1\n#def IN3 x0.3\n#def IN5 x2.5\n#def INW xw4\n#def IN27 x2.7\n"
    "#def OUT y0.1\n#def OUTW yw0\n#def OUT32 y3.2\n#def OUT37 y3.7\n#def OUTB y5\n#def SPARE y6.0\n#def CNT rw10\n"
)
"""Inputs of each width, X0's two bits apart in the list of inputs, X2's neighbours; outputs of bits, a byte, and a
word sharing Y0 with a bit; Y3 written only by a long (``WR YL0``), SPARE by the HMI alone."""
WIDE = ("INB", "INW", "ALL")
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
    st.tuples(
        st.just("input"), st.sampled_from(["IN0", "IN3", "IN5", "IN27", "INB", "INW", "ALL"]), st.integers(0, 70_000)
    ),
    st.tuples(st.just("terminal"), st.sampled_from(["X0", "X1", "X2", "X0.3", "XW4"]), st.integers(0, 255)),
    st.tuples(
        st.just("hmi"),
        st.sampled_from(["OUT", "OUTB", "SPARE", "OUT37", "Y3", "YW0", "X0", "U0", "X2", "R10"]),
        st.integers(0, 255),
    ),
    st.tuples(st.just("scan"), st.integers(1, 4)),
    st.tuples(st.just("run"), st.integers(1, 30_000_000)),
    st.tuples(st.just("event"), st.integers(1, 8)),
    st.sampled_from([("restart",), ("power",), ("write",)]),
)


def _apply(cpu: TecomatCPU, step: tuple) -> None:
    kind = step[0]
    if kind == "input" and step[1] in cpu.inputs:  # a bit driven as a bool or as a number (2 is on too)
        cpu.inputs[step[1]] = step[2] if step[1] in WIDE else (bool(step[2] & 1) if step[2] & 4 else step[2] & 3)
    elif kind == "terminal":
        cpu.set_input(step[1], step[2] & (1 if "." in step[1] else 255))
    elif kind == "hmi":
        cpu.write(step[1], step[2])
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

        def record(c: TecomatCPU) -> None:
            _io_as_memory_holds(c)
            rows[c].append((c.scan_end_ns, dict(vars(c.t)), dict(c.outputs)))

        for cpu in (head, plain):
            cpu.on_scan_end = record
    for step in [("scan", 1), *steps]:
        for cpu in (head, plain):
            _apply(cpu, step)
        assert _seen(head) == _seen(plain), (program, step)
        assert rows[head] == rows[plain], (program, step)


def _io_as_memory_holds(cpu: TecomatCPU) -> None:
    """At a cycle's end: each output is its operand in Y (a bit as a bool), each input's terminals hold the
    level the turnaround sampled (a bit on for any true level, a wide one cut to its registers)."""
    pad = cpu.machine.pad
    for name in cpu.output_names:
        op = cpu.symbols[name]
        assert cpu.outputs[name] == (read(pad, op) == 1 if op.width == "bit" else read(pad, op)), name
    if "ALL" not in cpu.inputs:  # (two names on one terminal: the one the wiring changed wins)
        for name, level in cpu.image_in.items():
            op = cpu.symbols[name]
            expected = (1 if level else 0) if op.width == "bit" else int(level) & (1 << 8 * SIZE[op.width]) - 1
            assert read(cpu.terminals, op) == expected, name


def test_a_program_with_a_jump_or_another_process_keeps_the_general_path():
    straight = TecomatCPU("LD X0.0\nWR Y0.0\n")
    jumping = TecomatCPU("LD X0.0\nJMC L1\nLD 1\nWR Y1\nL 1\nLD X0.0\nWR Y0.0\n")
    periodic = TecomatCPU("P 0\nLD X0.0\nWR Y0.0\nE 0\nP 5\nLD X0.1\nWR Y0.1\nE 5\n")
    assert straight._head is not None and new_controller()._head is not None  # (what the benchmark times)
    assert jumping._head is None and periodic._head is None
