"""The rung drawn is the logic that runs: every shipped Python solution of every exercise, drawn as a
ladder and the drawing run as LAD runs it (every contact read, left to right, top to bottom), does
exactly what the program's own networks do, on random input and memory states (hypothesis)."""

from __future__ import annotations

import ast

import pytest
from faithful import INTEGERS, run_side_by_side, scalar_paths, twin_cpus
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from exercises import all_exercises
from plcsim.frontends.python.program import Program
from plcsim.tags.types import Bool

CASES = [(ex, sol) for ex in all_exercises() for sol in ex.solutions if sol.path.suffix == ".py"]


def _constants(program: Program) -> list[int]:
    """The program's integer constants and their neighbours, so that random values hit its comparisons."""
    found = {0, 1}
    for node in ast.walk(program.tree):
        if isinstance(node, ast.Constant) and isinstance(node.value, int) and not isinstance(node.value, bool):
            found |= {node.value - 1, node.value, node.value + 1}
    return sorted(found)


def _value(dtype, constants):
    if dtype is Bool:
        return st.booleans()
    if dtype.name in INTEGERS:
        low, high = dtype.limits if hasattr(dtype, "limits") else (-(2**15), 2**15 - 1)
        near = [c for c in constants if low <= c <= high]
        return st.sampled_from(near) | st.integers(-3, 30).filter(lambda v: low <= v <= high)
    return st.sampled_from([0.0, 1.5, -2.0, 100.0])


@pytest.mark.parametrize(("exercise", "solution"), CASES, ids=[f"{e.number}-{s.name}" for e, s in CASES])
def test_the_ladder_does_what_the_program_does(exercise, solution):
    program = Program.from_file(solution.path)
    table = exercise.tag_table()
    paths = scalar_paths(twin_cpus(program, table, **exercise.cpu)[0])
    constants = _constants(program)
    writes = st.fixed_dictionaries({}, optional={p: _value(t, constants) for p, t in paths.items()})
    steps = st.lists(st.tuples(writes, st.sampled_from([0, 1, 5, 100, 1000, 3000])), min_size=1, max_size=6)

    @settings(max_examples=25, deadline=None, suppress_health_check=list(HealthCheck), database=None)
    @given(steps)
    def check(script):
        original, drawn, _ = twin_cpus(program, table, **exercise.cpu)
        run_side_by_side(original, drawn, script)

    check()
