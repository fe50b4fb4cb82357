"""Hostile programs against the CPU's time and memory: each is a load error or a STOP, never a hang.

Issue 9: ``9**9**9`` and an 80 000-line file ran into the grader's CPU limit, a deep expression was a
"grader error: RecursionError", a BaseException in a network was a grader error. The load time of a
large file is measured by ``python -m benchmarks`` (figure ``plc_load_80k_lines_s``), not here.
"""

from __future__ import annotations

import pytest

from plcsim import CPU, Program, Tag
from plcsim.core.errors import DeclarationError, ProgramError, SubsetError
from plcsim.frontends.python.subset import MAX_NESTING

PANEL = {"TL": Tag("%I0.0"), "LED": Tag("%Q0.0")}


def run(source: str) -> CPU:
    cpu = CPU(tags=PANEL, program=Program.from_source(source, "lab.py"))
    cpu.scan(2)
    return cpu


@pytest.mark.parametrize(
    ("expression", "words"),
    [
        pytest.param("9**9**9", "9 ** 387420489 is far beyond any PLC number", id="power-tower"),
        pytest.param("2**10**8", "2 ** 100000000 is far beyond", id="power"),
        pytest.param("'x' * 10**9", "str * 1000000000 would hold 1000000000 items", id="string-times"),
        pytest.param("1 << 10**10", "1 << 10000000000 is far beyond", id="shift"),
        pytest.param("(10**1000) * (10**1000)", "is far beyond", id="multiply"),
    ],
)
def test_a_huge_constant_is_refused_at_load_time(expression, words):
    with pytest.raises(SubsetError) as info:
        Program.from_source(f"def OB1(t):\n    x = {expression}\n", "lab.py")
    assert str(info.value).startswith("lab.py, line 2:")
    assert words in str(info.value)


@pytest.mark.parametrize(
    ("body", "words"),
    [
        pytest.param("x = 9\n    y = x ** x ** x", "9 ** 387420489", id="power"),
        pytest.param("x = [0]\n    y = x * 10**9", "list * 1000000000 would hold", id="list-times"),
        pytest.param("x = 'ab'\n    x *= 10**8", "str * 100000000", id="augmented"),
        pytest.param("x = 2\n    for i in range(20):\n        x = x * x", "is far beyond", id="squaring"),
        pytest.param("x = 1\n    y = x << 10**9", "1 << 1000000000", id="shift"),
    ],
)
def test_a_huge_result_at_run_time_stops_the_cpu_with_the_network(body, words):
    cpu = run(f"def OB1(t):\n    {body}\n    t.LED = True\n")
    assert cpu.mode == "STOP"
    assert words in cpu.error.message
    assert cpu.error.network == "1 (OB1)" and cpu.error.line is not None


def test_ordinary_arithmetic_is_unchanged():
    cpu = run("X = DInt(0)\nR = Real(0.0)\ndef OB1(t):\n    t.X = 3 * 4 + 2**10 + (1 << 4)\n    t.R = 2.5 * 2\n")
    assert cpu.read("X") == 12 + 1024 + 16
    assert cpu.read("R") == 5.0


def test_a_deep_expression_chain_is_a_subset_error_naming_the_line():
    deep = "+".join(["1"] * (MAX_NESTING + 20))
    with pytest.raises(SubsetError, match=r"lab.py, line 3: the code is nested too deeply \(more than 100 levels\)"):
        Program.from_source(f"def OB1(t):\n    x = 1\n    x = {deep}\n", "lab.py")


def test_an_expression_too_deep_for_the_parser_names_its_line_too():
    deep = "+".join(["t.TL"] * 20_000)
    with pytest.raises(SubsetError, match=r"lab.py, line 3: the code is nested too deeply"):
        Program.from_source(f"def OB1(t):\n    x = 1\n    x = {deep}\n", "lab.py")


def test_mutual_recursion_stops_the_cpu_with_the_network_named():
    cpu = run("def ping(t):\n    pong(t)\ndef pong(t):\n    ping(t)\ndef OB1(t):\n    ping(t)\n")
    assert cpu.mode == "STOP"
    assert "RecursionError" in cpu.error.message and "calls itself" in cpu.error.message
    assert cpu.error.task == "OB1" and cpu.error.network == "1 (OB1)"


def test_a_base_exception_from_a_network_stops_the_cpu(monkeypatch):
    # the subset cannot raise one itself; an instruction that does (a SystemExit deep in a library) still
    # must be a STOP with the network named, not a crash of the grader
    import plcsim.controllers.s7.instructions.arithmetic as arithmetic

    def leaving(x: float) -> float:
        raise SystemExit(3)

    monkeypatch.setitem(arithmetic.MATH_FUNCTIONS, "SQRT", leaving)
    monkeypatch.setitem(
        __import__("plcsim.controllers.s7.instructions", fromlist=["x"]).PURE_INSTRUCTIONS, "SQRT", leaving
    )
    cpu = run(
        "R = Real(0.0)\ndef first(t):\n    t.R = 1.0\ndef second(t):\n    t.R = SQRT(4.0)\nOB1 = [first, second]\n"
    )
    assert cpu.mode == "STOP"
    assert cpu.error.network == "2 (second)" and "SystemExit" in cpu.error.message


def test_an_endless_loop_is_a_watchdog_stop_not_a_hang():
    cpu = CPU(tags=PANEL, program="def OB1(t):\n    while True:\n        pass\n", watchdog_iterations=1000)
    cpu.scan()
    assert cpu.mode == "STOP" and cpu.error.event == "cycle time monitoring exceeded"


def test_module_level_cannot_loop_at_all():
    with pytest.raises(ProgramError, match=r"lab.py, line 1: a while loop at module level"):
        Program.from_source("while True:\n    pass\ndef OB1(t):\n    pass\n", "lab.py")


@pytest.mark.parametrize(
    ("body", "words"),
    [
        pytest.param("x = sum(range(10**15))", "range(...) of 1000000000000000 items", id="sum-range"),
        pytest.param("x = max(range(10**12))", "range(...) of", id="max-range"),
        pytest.param("f = '%0999999999d'\n    x = f % 1", "% formatting of text", id="percent-format"),
    ],
)
def test_builtins_that_loop_in_c_are_bounded(body, words):
    cpu = run(f"def OB1(t):\n    {body}\n")
    assert cpu.mode == "STOP" and words in cpu.error.message


@pytest.mark.parametrize("method", ["ljust", "rjust", "center", "zfill", "expandtabs", "to_bytes"])
def test_size_taking_text_builders_are_refused(method):
    with pytest.raises(SubsetError, match=rf"line 2: the attribute .{method} is not available"):
        Program.from_source(f"def OB1(t):\n    x = 'x'.{method}(10**9)\n", "lab.py")


def test_modulo_still_computes_numbers():
    cpu = run("X = Int(0)\ndef OB1(t):\n    t.X = 17 % 5 + MOD(7, 4)\n")
    assert cpu.read("X") == 2 + 3


@pytest.mark.parametrize(
    "declaration",
    [
        "A = DB(X=Array(0, 100000000, Int))",
        "A = DB(X=Array(0, 2000, Array(0, 2000, Bool)))",
        "N = UDT(" + ", ".join(f"M{i}=Array(0, 999, Int)" for i in range(10)) + ")\nA = DB(X=Array(0, 200, N))",
    ],
)
def test_a_declaration_too_big_for_any_plc_is_refused_before_it_is_built(declaration):
    with pytest.raises(DeclarationError, match=r"lab.py, line \d+: A brings the program to \d+ values; a program may"):
        Program.from_source(declaration + "\ndef OB1(t):\n    pass\n", "lab.py")
