"""Student-side fixes of issue 10 and the input-write rule of issue 9.

* ``t.T.ET > "500ms"`` compares with a TIME (folded at load time); a bad literal is a load error.
* An undeclared instance says "declare it: ``TRIG = R_TRIG()``", with the type guessed from the box.
* Edge memory bits and MOVE outputs accept ``t.X`` as well as ``"X"``.
* A store into an input tag is a load warning naming the line, or an error when the CPU says so.
"""

from __future__ import annotations

import pytest

from plcsim import CPU, Program, Tag
from plcsim.core.errors import ConfigurationError, ProgramError, UnknownTagError

PANEL = {"TL": Tag("%I0.0"), "LED": Tag("%Q0.0")}


def cpu_for(source: str, **options) -> CPU:
    return CPU(tags=PANEL, program=Program.from_source(source, "lab.py"), **options)


@pytest.mark.parametrize("compare", ["t.T.ET > '500ms'", "'500ms' < t.T.ET", "t.T.ET >= 'T#501ms'"])
def test_a_timer_et_compares_with_a_time_literal(compare):
    cpu = cpu_for(f"T = IEC_TIMER()\ndef OB1(t):\n    t.T.TON(IN=t.TL, PT='2s')\n    t.LED = {compare}\n")
    cpu.set_input("TL", True)
    cpu.run("500ms")
    assert cpu.outputs["LED"] is False and cpu.mode == "RUN"
    cpu.run("2ms")
    assert cpu.outputs["LED"] is True


def test_a_time_tag_compares_with_a_time_literal():
    cpu = cpu_for("D = Time(1500)\ndef OB1(t):\n    t.LED = t.D == '1s500ms'\n")
    cpu.scan()
    assert cpu.outputs["LED"] is True


def test_a_bad_time_literal_in_a_comparison_is_a_load_error_with_the_fix():
    with pytest.raises(ProgramError) as info:
        cpu_for("T = IEC_TIMER()\ndef OB1(t):\n    t.T.TON(IN=t.TL, PT='2s')\n    t.LED = t.T.ET > '5 sec'\n")
    assert str(info.value).startswith("lab.py, line 4:")
    assert "TIME literal such as '500ms'" in str(info.value)


def test_a_string_compared_with_a_string_tag_is_left_alone():
    cpu = cpu_for("S = String('ab')\ndef OB1(t):\n    t.LED = t.S == 'ab'\n")
    cpu.scan()
    assert cpu.outputs["LED"] is True


@pytest.mark.parametrize(
    ("call", "declaration"),
    [
        ("t.TRIG(CLK=t.TL)", "`TRIG = R_TRIG()`, then call t.TRIG.R_TRIG(...)"),
        ("t.TON_X.TON(IN=t.TL, PT='1s')", "`TON_X = IEC_TIMER()`, then call t.TON_X.TON(...)"),
        ("t.T1(IN=t.TL, PT='1s')", "`T1 = IEC_TIMER()`"),
        ("t.C1.CTU(CU=t.TL, PV=3)", "`C1 = IEC_COUNTER()`, then call t.C1.CTU(...)"),
        ("t.C2(CU=t.TL, PV=3)", "`C2 = IEC_COUNTER()`"),
        ("t.FALL.F_TRIG(CLK=t.TL)", "`FALL = F_TRIG()`"),
    ],
)
def test_an_undeclared_instance_says_how_to_declare_it(call, declaration):
    with pytest.raises(UnknownTagError) as info:
        cpu_for(f"def OB1(t):\n    t.LED = {call}\n")
    message = str(info.value)
    assert message.startswith("lab.py, line 2: no instance")
    assert f"declare it at module level: {declaration}" in message


def test_a_misspelt_instance_also_gets_the_nearest_name():
    with pytest.raises(UnknownTagError, match=r"no instance 'TON_AA'; did you mean 'TON_A'\?"):
        cpu_for("TON_A = IEC_TIMER()\ndef OB1(t):\n    t.LED = t.TON_AA.TON(IN=t.TL, PT='1s')\n")


@pytest.mark.parametrize("memory", ["'SB1'", "t.SB1"])
def test_an_edge_memory_bit_may_be_written_as_a_tag(memory):
    cpu = cpu_for(f"SB1 = Bool()\nN = Int(0)\ndef OB1(t):\n    if P(t.TL, {memory}):\n        t.N += 1\n")
    for level in (True, True, False, True, False):
        cpu.set_input("TL", level)
        cpu.scan()
    assert cpu.read("N") == 2 and cpu.read("SB1") is False


@pytest.mark.parametrize("out", ["'A', 'DATA.B', 'DATA.ARR[2]'", "t.A, t.DATA.B, t.DATA.ARR[2]"])
def test_move_outputs_may_be_written_as_tags(out):
    cpu = cpu_for(f"A = Int(0)\nDATA = DB(B=Int, ARR=Array(0, 3, Int))\ndef OB1(t):\n    MOVE(7, {out})\n")
    cpu.scan()
    assert (cpu.read("A"), cpu.read("DATA.B"), cpu.read("DATA.ARR[2]"), cpu.read("DATA.ARR[1]")) == (7, 7, 7, 0)


def test_a_tag_as_edge_memory_must_exist():
    with pytest.raises(UnknownTagError, match=r"lab.py, line 2: no tag 'SB9'"):
        cpu_for("def OB1(t):\n    t.LED = P(t.TL, t.SB9)\n")


def test_writing_an_input_is_a_load_warning_naming_the_line():
    cpu = cpu_for("def OB1(t):\n    t.LED = t.TL\n    t.TL = True\n")
    (warning,) = [w for w in cpu.warnings if "writes the input" in w]
    assert warning.startswith("lab.py, line 3: the program writes the input TL (%I0.0)")


@pytest.mark.parametrize("store", ["t.TL = True", "t['TL'] = True", "MOVE(True, 'TL')", "MOVE(True, t.TL)"])
def test_writing_an_input_is_an_error_when_the_cpu_says_so(store):
    with pytest.raises(ProgramError, match=r"lab.py, line 3: the program writes the input TL"):
        cpu_for(f"def OB1(t):\n    t.LED = t.TL\n    {store}\n", input_writes="error")


def test_input_writes_option_is_checked():
    with pytest.raises(ConfigurationError, match="input_writes 'maybe'"):
        CPU(tags=PANEL, input_writes="maybe")
