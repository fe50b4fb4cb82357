"""A local that names a data block (``s = t.DB`` at the top of a network, never bound again): in a task's merged
function it reads and writes as the block itself (typed stores, reads the typing knows are Bool), with the same
tags, faults and messages as the networks run one by one; a local that is not provably the block keeps today's
path (issue 29)."""

from __future__ import annotations

import pytest

import plcsim.frontends.python.pipeline
from plcsim import CPU, Int, Tag

BLOCKS = """
D = DB(A=Bool(False), B=Bool(False), N=Int(0), R=Real(0.0), W=Time("0ms"))
E = DB(A=Bool(False), B=Bool(False), N=Int(0), R=Real(0.0), W=Time("0ms"))
T0 = IEC_TIMER()

"""


def table() -> dict[str, Tag]:
    return {"I0": Tag("%I0.0"), "I1": Tag("%I0.1"), "Q0": Tag("%Q0.0"), "Q1": Tag("%Q0.1"), "M0": Tag("%MW10", Int)}


def program(n1: str, n0: str = "t.Q1 = t.I1") -> str:
    """Two networks (so that OB1 is merged): ``n0`` and ``n1``, each given as its body's lines."""
    body = "\n".join(f"    {line}" for line in n1.strip().splitlines())
    return BLOCKS + f"def n0(t):\n    {n0}\n\n\ndef n1(t):\n{body}\n\n\nOB1 = [n0, n1]\n"


def run(source: str, merged: bool, scans: int = 6, inputs: dict[str, bool] | None = None) -> tuple:
    """Mode, diagnostics (event, message, network, line) and every tag and block member at the end."""
    pipeline = plcsim.frontends.python.pipeline
    with pytest.MonkeyPatch.context() as patch:
        patch.setattr(pipeline, "MAX_MERGED_STATEMENTS", 5000 if merged else 0)
        cpu = CPU(tags=table(), program=source)
    assert (cpu._ob1.merged is not None) is merged
    cpu.inputs.update(inputs or {"I0": True})
    for _ in range(scans):
        cpu.scan()
    values = {k: v for k, v in cpu.t.__dict__.items() if isinstance(v, bool | int | float)}
    for block in ("D", "E"):
        values.update({f"{block}.{k}": v for k, v in getattr(cpu.t, block).__dict__.items() if not k.startswith("_")})
    diagnostics = [(d.event, d.message, d.network, d.line) for d in cpu.diagnostics]
    return cpu.mode, diagnostics, values


def both_ways(source: str, **kwargs) -> tuple:
    """The run merged, after checking that it is the run of the networks one by one (messages too: a local
    is named as the program wrote it, not by the merged function's name for it)."""
    merged = run(source, True, **kwargs)
    assert merged == run(source, False, **kwargs)
    return merged


def merged_names(source: str) -> set[str]:
    """The global names the merged OB1 calls or reads (``_store``, ``_to_Bool`` ...)."""
    return set(CPU(tags=table(), program=source)._ob1.merged.__code__.co_names)


ALIAS = """
s = t.D
s.N = s.N + 1
t.Q0 = s.A and not s.B
s.A = t.I0 and s.N > 2
s.R = s.R * 1.1 + 0.1
t.M0 = s.N
if s.N > 3:
    s.B = True
"""


def test_an_alias_runs_as_the_block_written_out():
    """Same tags as ``t.D.X`` written out; the merged code stores and reads the block directly: no slow store
    through the object, no conversion of a Bool the typing now knows."""
    written = ALIAS.replace("s = t.D", "x = t.D").replace("s.", "t.D.")
    alias = both_ways(program(ALIAS))
    assert alias == both_ways(program(written))
    assert alias[0] == "RUN" and alias[2]["D.B"] is True and alias[2]["D.N"] == 6 and alias[2]["Q0"] is False
    assert not merged_names(program(ALIAS)) & {"_store", "_to_Bool"}


FAULT = """
s = t.D
s.N = s.N + 1
s.A = s.N > 1
t.Q0 = 10 // (3 - s.N) > 0
s.B = s.N > 2
"""


def test_a_fault_in_the_middle_of_a_network_leaves_the_tags_as_written_out():
    """On the third scan the division fails after N and A were stored and before B: STOP at the student's line,
    the tags as the statements before the fault left them, as with ``t.D.X`` written out."""
    written = FAULT.replace("s = t.D", "x = t.D").replace("s.", "t.D.")
    mode, diagnostics, values = both_ways(program(FAULT))
    assert (mode, diagnostics, values) == both_ways(program(written))
    assert mode == "STOP" and values["D.N"] == 3 and values["D.A"] is True and values["D.B"] is False
    fault = next(d for d in diagnostics if d[0] == "error in the program")
    line = program(FAULT).splitlines().index("    t.Q0 = 10 // (3 - s.N) > 0") + 1
    assert "ZeroDivisionError" in fault[1] and fault[3] == line


@pytest.mark.parametrize(
    ("store", "message"),
    [
        ("s.A = t.M0 + 2", "D.A is Bool; cannot store int 2"),  # converted when it runs
        ("s.A = 1", "D.A is Bool; cannot store int 1"),  # a constant: refused when it runs, not at load, as today
    ],
)
def test_a_type_error_through_the_alias_stops_at_the_students_line(store: str, message: str):
    source = program(f"s = t.D\nt.Q0 = s.B\n{store}")
    mode, diagnostics, _ = both_ways(source, scans=1)
    fault = next(d for d in diagnostics if d[0] == "error in the program")
    assert mode == "STOP" and message in fault[1]
    assert fault[3] == source.splitlines().index(f"    {store}") + 1 and f"line {fault[3]}" in fault[1]


def test_a_name_bound_again_in_a_branch_is_no_alias():
    """``s`` names E after the branch: the store goes into E, not into D (a pass that took ``s`` for D would
    store into D)."""
    source = program("s = t.D\nif t.I0:\n    s = t.E\ns.A = True\nt.Q0 = s.B")
    _, _, values = both_ways(source)
    assert values["E.A"] is True and values["D.A"] is False
    assert "_store" in merged_names(source)
    _, _, values = both_ways(source, inputs={"I0": False})
    assert values["D.A"] is True and values["E.A"] is False


@pytest.mark.parametrize(
    "body",
    [
        "if t.I0:\n    s = t.D\ns.A = True",  # bound inside an if: with I0 False, s is unbound
        "t.Q0 = s.A\ns = t.D\ns.A = True",  # read before its binding
        "for k in range(1):\n    s = t.D\ns.A = True",  # bound in a loop
        "s = t.D\ns.A = True\ns = t.E\ns.B = True",  # bound twice
        "s = t.D\ns.A = True\ns, k = t.E, 1\ns.B = True",  # bound again by a tuple
        "s = t.D\nwhile t.M0 < 3:\n    t.M0 = t.M0 + 1\n    s = t.E\ns.A = True",  # bound again in a loop
    ],
)
def test_a_name_not_provably_the_block_keeps_todays_path(body: str):
    source = program(body)
    mode, diagnostics, values = both_ways(source, inputs={"I0": False})
    assert "_store" in merged_names(source)
    if body.startswith(("if", "t.Q0")):
        fault = next(d for d in diagnostics if d[0] == "error in the program")
        line = next(i for i, text in enumerate(source.splitlines(), 1) if "s.A" in text and "def" not in text)
        assert mode == "STOP" and "UnboundLocalError" in fault[1] and fault[3] == line
    else:
        assert mode == "RUN" and values["D.A"] is True


def test_a_name_bound_to_something_that_is_no_block_keeps_todays_path():
    """``s = t.T0`` (a timer instance), ``s = t.M0`` (a word): no block, the local stays a local."""
    timer = program("s = t.T0\ns.TON(IN=t.I0, PT='5ms')\nt.Q0 = s.Q")
    _, _, values = both_ways(timer)
    assert values["Q0"] is True
    word = program("s = t.M0\nt.M0 = s + 1\nt.Q0 = s > 2")
    _, _, values = both_ways(word)
    assert values["M0"] == 6 and values["Q0"] is True


def test_a_time_member_read_through_the_local_is_compared_as_today():
    """``s.W < "5ms"``: only a TIME the typing knows has its literal folded, so through the local the comparison of
    a number with a text fails when it runs, merged or not (written ``t.D.W`` it would compare two TIMEs)."""
    mode, diagnostics, _ = both_ways(program('s = t.D\nt.Q0 = s.W < "5ms"'), scans=1)
    assert mode == "STOP" and any("TypeError" in message for _, message, _, _ in diagnostics)
