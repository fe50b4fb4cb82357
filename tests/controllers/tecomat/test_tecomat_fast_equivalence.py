"""The generated code (``plcsim.controllers.tecomat.fused``) and the plain closures compute the same machine: random
small IL programs over every instruction the generator handles (and some it hands to closures: tables,
stack switches, long operands, forward jumps), run on random inputs, leave the same scratchpad, stacks, active stack and
block state after every cycle."""

from __future__ import annotations

from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from plcsim.controllers.tecomat.cpu import TecomatCPU

BITS = [
    f"{area}{n}.{b}"
    for area, n in (("X", 0), ("X", 1), ("Y", 0), ("R", 0), ("R", 1), ("S", 0), ("S", 1))
    for b in (0, 3, 7)
]
BYTES = ["X0", "X1", "Y0", "Y1", "R0", "R1", "R3", "S0", "S1", "R10", "R21"]
WORDS = ["XW0", "RW0", "RW1", "YW0", "SW0", "RW10", "RW20", "RW23"]
"""(RW10, R21, RW20 and RW23 share registers with the blocks' words: the generated code must not hold them
across a block.)"""
TARGET_BITS = [b for b in BITS if b[0] in "YRS"]
TARGET_BYTES = [b for b in BYTES if b[0] in "YRS"]
TARGET_WORDS = ["RW0", "RW1", "YW0", "SW0", "RW10", "RW20", "RW23"]
immediates = st.integers(0, 0xFFFF).map(str)
FLAGS = ["S0.0", "S0.1", "S0.2", "S0.3", "S0", "SW0", "S1.0"]
"""The flags, read often: the generated code defers S0 writes and knows when S0.3 is 0."""
readable = st.one_of(st.sampled_from(BITS + BYTES + WORDS), st.sampled_from(FLAGS), immediates)
logic_operand = st.one_of(st.sampled_from(BITS + BYTES), immediates)
compare_operand = st.one_of(st.sampled_from(BYTES + WORDS), st.integers(0, 300).map(str))


def _instructions() -> st.SearchStrategy[str]:
    return st.one_of(
        st.tuples(st.sampled_from(["LD", "LDC"]), readable).map(" ".join),
        st.tuples(
            st.sampled_from(["WR", "WRC", "PUT"]), st.sampled_from(TARGET_BITS + TARGET_BYTES + TARGET_WORDS)
        ).map(" ".join),
        st.tuples(st.sampled_from(["AND", "ANC", "OR", "ORC", "XOR", "XOC"]), logic_operand).map(" ".join),
        st.sampled_from(["AND", "OR", "XOR", "NEG", "STK", "SWP", "FLG", "NXT", "PRV", "ADD", "EQ", "LT", "GT"]),
        st.tuples(st.sampled_from(["SET", "RES", "LET"]), st.sampled_from(TARGET_BITS + TARGET_BYTES)).map(" ".join),
        st.tuples(st.sampled_from(["EQ", "LT", "GT", "ADD"]), compare_operand).map(" ".join),
        st.tuples(st.sampled_from(["LD", "ANC", "WR", "SET"]), st.sampled_from(FLAGS[:4])).map(" ".join),
        st.sampled_from(["EQ 5", "LT 300", "GT 2"]),
        st.integers(1, 3).map(lambda n: f"POP {n}"),
        st.sampled_from(["CHG A", "CHG B", "CHG BS", "CHG AS"]),
        st.sampled_from(["CTU RW10", "CTD RW12", "CNT RW14", "SFL RW16", "SFR RW18"]),
        st.sampled_from(["TON RW20.0", "TOF RW22.0", "IMP RW24.1", "RTO RW26.0", "TOF RW28.0"]),
        st.sampled_from(["LTB tab", "FTB tab"]),
        st.sampled_from(["LD RL0", "LDC RL9", "LD XL0", "WR RL0", "WRC RL9", "PUT RL20", "WR YL0"]),
    )


@st.composite
def programs(draw) -> str:
    """A program of a few segments; a segment may be skipped by a forward conditional jump to its end."""
    lines = ["#table byte tab = 3, 15, 30, 65, 137, 240"]
    for k in range(draw(st.integers(1, 3))):
        jump = draw(st.sampled_from([None, "JMD", "JMC"]))
        if jump:
            lines.append(f"{jump} L{k}")
        lines += draw(st.lists(_instructions(), min_size=1, max_size=14))
        if jump:
            lines.append(f"L {k}")
    return "\n".join(lines) + "\n"


def _state(cpu: TecomatCPU) -> tuple:
    m = cpu.machine
    blocks = sorted((b.kind, b.index, b.prev, b.prev2, b.timing, b.acc, b.last_pass, b.overflow) for b in m.blocks)
    areas = {name: bytes(area) for name, area in m.pad.areas.items()}
    return areas, [list(s) for s in m.stacks], m.active, m.saved_flags, blocks, cpu.mode


@settings(max_examples=300, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(program=programs(), inputs=st.lists(st.binary(min_size=2, max_size=2), min_size=1, max_size=8), data=st.data())
def test_the_generated_code_and_the_closures_leave_the_same_machine(program, inputs, data):
    options = {"cycle": "7ms", "pop_fill_keeps_a7": data.draw(st.booleans()), "ci_in_compare": data.draw(st.booleans())}
    fast, plain = TecomatCPU(program, **options), TecomatCPU(program, fuse=False, **options)
    for x in inputs:
        for cpu in (fast, plain):
            cpu.set_input("X0", x[0])
            cpu.set_input("X1", x[1])
            cpu.scan()
        assert _state(fast) == _state(plain), program


def test_the_benchmark_workload_runs_the_same_on_both_paths():
    """benchmarks/workload.il (what the tecomat benchmark times) on its input schedule, 3000 cycles."""
    from benchmarks import workload
    from benchmarks.tecomat import SOURCE
    from plcsim.controllers.choice import controller_for
    from plcsim.frontends.il import program_text

    fast, plain = (controller_for(program_text(SOURCE, "workload.il"), workload.tags(), fuse=f) for f in (True, False))
    outputs = set()
    for changes in workload.build_schedule(3000):
        for cpu in (fast, plain):
            cpu.inputs.update(changes or {})
            cpu.scan()
        assert _state(fast) == _state(plain) and fast.outputs == plain.outputs
        outputs.add(tuple(fast.outputs.values()))
    assert len(outputs) > 100  # the program is never idle
