"""Hostile programs against typed stores: no path lands a function or the integer 2 in a BOOL.

Issue 9: a name rebound by a nested ``def`` or a decorator skipped the BOOL conversion. Every way a
name can be bound, and every way a value can reach a tag, is tried here; each ends in a load-time
refusal or a run-time STOP that names the network and the line, and the output stays a bool.
"""

from __future__ import annotations

import pytest

from plcsim import CPU, Program, Tag
from plcsim.core.errors import ProgramError, SubsetError
from plcsim.tags.types import Bool, Int

PANEL = {"TL": Tag("%I0.0"), "LED": Tag("%Q0.0")}


def run(source: str) -> CPU:
    cpu = CPU(tags=PANEL, program=Program.from_source(source, "lab.py"))
    cpu.set_input("TL", True)
    cpu.scan(2)
    return cpu


def refusal(source: str) -> str:
    """Why the program cannot put a non-bool into LED: its load-time error, or the STOP's message (a line named
    either way, and LED still FALSE)."""
    try:
        cpu = run(source)
    except ProgramError as exc:
        assert str(exc).startswith("lab.py, line ")
        return str(exc)
    assert cpu.mode == "STOP" and cpu.error.line is not None
    assert cpu.t.LED is False
    return cpu.error.message


@pytest.mark.parametrize(
    "source",
    [
        pytest.param("def OB1(t):\n    x = t.TL\n    def x():\n        pass\n    t.LED = x\n", id="nested-def"),
        pytest.param("def OB1(t):\n    x = t.TL\n    for x in [2]:\n        pass\n    t.LED = x\n", id="for-target"),
        pytest.param("def OB1(t):\n    x = t.TL\n    x, y = 2, 3\n    t.LED = x\n", id="tuple-target"),
        pytest.param("def OB1(t):\n    x = t.TL\n    [x, y] = [2, 3]\n    t.LED = x\n", id="list-target"),
        pytest.param("def OB1(t):\n    x = t.TL\n    x += 1\n    t.LED = x\n", id="augassign"),
        pytest.param("def OB1(t):\n    def f(x=2):\n        return x\n    t.LED = f()\n", id="default-arg"),
        pytest.param("def OB1(t):\n    def f(x=2):\n        t.LED = x\n    f()\n", id="default-arg-store"),
        pytest.param("def OB1(t):\n    t['LED'] = 2\n", id="subscript"),
        pytest.param("def OB1(t):\n    x = t\n    x.LED = 2\n", id="alias-of-t"),
        pytest.param("def OB1(t):\n    def inner(t):\n        t.LED = 2\n    inner(t)\n", id="inner-t"),
        pytest.param("def f(t):\n    return 2\ndef OB1(t):\n    t.LED = f(t)\n", id="helper-result"),
        pytest.param("def OB1(t):\n    t.LED = t.TL and 2\n", id="and-with-int"),
        pytest.param("def OB1(t):\n    t.LED = 2 if t.TL else False\n", id="ifexp"),
    ],
)
def test_a_non_bool_never_lands_in_a_bool(source):
    assert "LED is Bool; cannot store" in refusal(source)


@pytest.mark.parametrize(
    ("source", "line", "words"),
    [
        pytest.param("def OB1(t):\n    P = 2\n", 2, "P is the name of an instruction", id="local-shadows-P"),
        pytest.param("def P(t):\n    return 2\nOB1 = [P]\n", 1, "P is the name of an instruction", id="def-P"),
        pytest.param("def OB1(t):\n    def IN_RANGE(a, b, c):\n        return 2\n", 2, "IN_RANGE is", id="inner"),
        pytest.param("def OB1(t):\n    for N in [max]:\n        pass\n", 2, "N is the name", id="for-N"),
        pytest.param("def OB1(t):\n    def f(P_TRIG):\n        pass\n", 2, "P_TRIG is", id="param"),
        pytest.param("def OB1(t):\n    min = 2\n", 2, "min is the name of", id="builtin"),
        pytest.param("def OB1(t):\n    for t.LED in [2]:\n        pass\n", 2, "a for loop counts", id="for-tag"),
        pytest.param("def OB1(t):\n    t.__dict__['LED'] = 2\n", 2, ".__dict__", id="dunder-dict"),
        pytest.param("def OB1(t):\n    @label('x')\n    def f():\n        pass\n", 2, "decorators", id="deco"),
        pytest.param("def OB1(t):\n    (x := 2)\n", 2, ":= operator", id="walrus"),
        pytest.param("def OB1(t):\n    Int.coerce = OB1\n", 2, "Int.coerce cannot be assigned", id="coerce"),
        pytest.param("def OB1(t):\n    TIME.x = 1\n", 2, "TIME.x cannot be assigned", id="function-attr"),
        pytest.param("def OB1(t):\n    DTL.members['X'] = 1\n", 2, "cannot be assigned", id="type-members"),
        pytest.param("T = IEC_TIMER()\ndef OB1(t):\n    t.T.TON.x = 1\n", 3, "t.T.TON has no members", id="box"),
        pytest.param("def OB1(t):\n    t.LED.x = 1\n", 2, "t.LED has no members", id="bool-member"),
        pytest.param("def OB1(t):\n    t.TON_A.TON.__x = 1\n", 2, ".__x", id="dunder-box"),
    ],
)
def test_stores_outside_tags_and_locals_are_refused_at_load_time(source, line, words):
    with pytest.raises(ProgramError) as info:
        Program.from_source(source, "lab.py") and run(source)
    message = str(info.value)
    assert message.startswith(f"lab.py, line {line}:"), message
    assert words in message


def test_a_network_called_with_something_else_than_t_cannot_write_into_it():
    source = "def set_led(t):\n    t.LED = True\ndef OB1(t):\n    set_led(Int)\n"
    cpu = run(source)
    assert cpu.mode == "STOP"
    assert "called with ElementaryType instead of the tags" in cpu.error.message
    assert "LED" not in vars(Int) and Int.coerce(3) == 3


def test_a_type_shared_by_every_program_cannot_be_changed_through_a_method():
    cpu = run("def OB1(t):\n    DTL.members.clear()\n")
    assert cpu.mode == "STOP" and "mappingproxy" in cpu.error.message
    from plcsim.tags.types import DTL

    assert "YEAR" in DTL.members


def test_bool_locals_still_skip_the_check_when_they_only_hold_bools():
    # the optimisation the compiler keeps: a local bound only to Bool expressions is stored unchecked
    cpu = run("EDGE_M = Bool()\ndef OB1(t):\n    x = P(t.TL, 'EDGE_M')\n    y = x and t.TL\n    t.LED = y\n")
    assert cpu.mode == "RUN"
    assert cpu.outputs["LED"] is False  # the edge came in scan 1; scan 2 sees none
    assert Bool.coerce(True) is True


def test_refused_programs_name_the_fix_in_words():
    with pytest.raises(SubsetError, match="choose another name"):
        Program.from_source("def OB1(t):\n    P = 2\n", "lab.py")


def test_shared_types_are_read_only_even_for_the_host():
    from plcsim.tags.types import String

    for dtype in (Int, Bool, String):
        with pytest.raises(AttributeError, match="is read-only"):
            dtype.coerce = print
    assert Int.coerce(32768) == -32768


@pytest.mark.parametrize(
    ("declaration", "call", "member"),
    [
        ("T = IEC_TIMER()", "t.T.TON(IN=2, PT='1s')", "T.IN is Bool"),
        ("T = IEC_TIMER()", "t.T.TOF(IN=OB1, PT='1s')", "T.IN is Bool"),
        ("T = IEC_TIMER()", "t.T.TP(IN=[1], PT='1s')", "T.IN is Bool"),
        ("T = IEC_TIMER()", "t.T.TONR(IN=True, PT='1s', R=3)", "T.R is Bool"),
        ("C = IEC_COUNTER()", "t.C.CTU(CU=2, PV=3)", "C.CU is Bool"),
        ("C = IEC_COUNTER()", "t.C.CTD(CD=True, LD=OB1, PV=3)", "C.LD is Bool"),
        ("C = IEC_COUNTER()", "t.C.CTUD(CU=True, CD=1, PV=3)", "C.CD is Bool"),
        ("E = R_TRIG()", "t.E.R_TRIG(CLK=OB1)", "E.CLK is Bool"),
        ("E = F_TRIG()", "t.E.F_TRIG(CLK=2)", "E.CLK is Bool"),
        ("C = IEC_COUNTER()", "t.C.CTU(CU=True, PV=10**6)", "PV 1000000 is outside the count type's range"),
    ],
)
def test_a_box_input_of_the_wrong_type_stops_the_cpu_instead_of_landing_in_the_instance(declaration, call, member):
    cpu = run(f"{declaration}\ndef OB1(t):\n    t.LED = {call}\n")
    assert cpu.mode == "STOP" and member in cpu.error.message
    name = declaration.split()[0]
    for key in ("IN", "R", "CU", "CD", "LD", "CLK", "Stat_Bit"):
        value = getattr(getattr(cpu.t, name), key, False)
        assert value is True or value is False, (key, value)
