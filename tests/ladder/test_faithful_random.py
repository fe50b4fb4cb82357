"""The faithfulness proof on programs hypothesis writes: random conditions (series, parallel, NOT, compares,
IN_RANGE, edge contacts anywhere), coils, set/reset forks, nested ifs, timer boxes and locals. Whatever the
builder draws as a rung must run as the program runs; what it cannot draw faithfully must become a text box
(which runs as written), so the two CPUs agree on every random state."""

from __future__ import annotations

from faithful import run_side_by_side, twin_cpus
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from plcsim import Int, Tag
from plcsim.frontends.python.program import Program
from plcsim.tags import TagTable

TAGS = {
    "S1": Tag("%I0.0"),
    "S2": Tag("%I0.1"),
    "S3": Tag("%I0.2"),
    "D1": Tag("%Q0.0"),
    "D2": Tag("%Q0.1"),
    "M1": Tag("%M0.0"),
    "M2": Tag("%M0.1"),
    "E1": Tag("%M1.0"),
    "E2": Tag("%M1.1"),
    "N": Tag("%MW10", Int),
}
LEAVES = [
    "t.S1",
    "t.S2",
    "t.S3",
    "t.M1",
    "t.D1",
    "t.N >= 2",
    "t.T.Q",
    "t.T.ET > 3",
    'P(t.S1, "E1")',
    'N(t.S2, "E2")',
    "IN_RANGE(1, t.N, 3)",
]
CONDITIONS = st.recursive(
    st.sampled_from(LEAVES),
    lambda inner: st.one_of(
        st.tuples(inner, inner).map(lambda ab: f"({ab[0]} and {ab[1]})"),
        st.tuples(inner, inner).map(lambda ab: f"({ab[0]} or {ab[1]})"),
        inner.map(lambda a: f"(not {a})"),
    ),
    max_leaves=5,
)


def _statement(kind: int, a: str, b: str) -> list[str]:
    return [
        [f"t.D1 = {a}"],
        [f"if {a}:", "    t.D2 = True", "    t.M1 = False"],
        [f"if {a}:", f"    if {b}:", "        t.M2 = True", "    t.N = t.N + 1"],
        [f'if t.T.TON(IN={a}, PT="5ms"):', "    t.D2 = False"],
        [f"x = {a}", "t.M2 = x or t.S3"],
        [f"if {a}:", "    t.N = 0", "    t.M1 = True"],
        [f'q = t.T.TON(IN={a}, PT="5ms")', f"t.D1 = q and {b}"],
    ][kind]


PROGRAMS = st.lists(
    st.tuples(st.integers(0, 6), CONDITIONS, CONDITIONS).map(lambda k: _statement(*k)), min_size=1, max_size=4
).map(lambda body: "T = IEC_TIMER()\n\ndef OB1(t):\n" + "".join(f"    {line}\n" for s in body for line in s))
WRITES = st.fixed_dictionaries(
    {},
    optional={
        **{name: st.booleans() for name in ("S1", "S2", "S3", "M1", "M2", "D1", "D2", "E1", "E2")},
        "N": st.integers(-1, 5),
    },
)
STEPS = st.lists(st.tuples(WRITES, st.sampled_from([0, 1, 3, 10])), min_size=1, max_size=8)


def _table() -> TagTable:
    table = TagTable()
    for name, tag in TAGS.items():
        table.add(name, tag)
    return table


@settings(max_examples=150, deadline=None, suppress_health_check=list(HealthCheck), database=None)
@given(PROGRAMS, STEPS)
def test_random_programs_run_the_same_as_their_ladder(source, steps):
    program = Program(source, "random.py")
    original, drawn, _ = twin_cpus(program, _table())
    run_side_by_side(original, drawn, steps)
