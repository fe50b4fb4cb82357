"""Golden tests: a student's mistakes give clear errors (load time) or a clear STOP (run time).

Rules these tests pin:

* Load time: an unknown tag is reported with the file, the line and the nearest names; a syntax
  error with its line; anything outside the PLC subset of Python (imports, open/eval, dunder
  attributes, classes, try, global, lambda ...) is a SubsetError naming the line; a bad address or a
  type that does not fit the address is an AddressError / DeclarationError.
* Run time: a store of the wrong type (a number into a BOOL, a BOOL into an INT) stops the CPU with a
  diagnostic naming the network, the line and the message.
* An edge instruction or FB call behind ``and``/``or`` gets a load warning: Python would skip it.
"""

from __future__ import annotations

import pytest

from plcsim import CPU, Program, Tag
from plcsim.core.errors import AddressError, DeclarationError, ProgramError, SubsetError, UnknownTagError

PANEL = {"TLACIDLO": Tag("%I0.0"), "LED": Tag("%Q0.0")}


def load(source: str, filename: str = "lab1.py") -> CPU:
    return CPU(tags=PANEL, program=Program.from_source(source, filename))


@pytest.mark.parametrize(
    ("source", "line", "hint"),
    [
        pytest.param("def OB1(t):\n    t.LED = t.TLACIDO\n", 2, "did you mean 'TLACIDLO'", id="typo-read"),
        pytest.param("def OB1(t):\n    t.LEDD = True\n", 2, "did you mean 'LED'", id="typo-store"),
        pytest.param("D = DB(CISLO=Int)\ndef OB1(t):\n    t.D.CISLA += 1\n", 3, "did you mean 'CISLO'", id="db-member"),
        pytest.param("T = IEC_TIMER()\ndef OB1(t):\n    t.LED = t.T.QQ\n", 3, "did you mean 'Q'", id="timer-member"),
    ],
)
def test_unknown_tag_at_load_time_names_file_line_and_nearest(source, line, hint):
    with pytest.raises(UnknownTagError) as info:
        load(source)
    message = str(info.value)
    assert message.startswith(f"lab1.py, line {line}:")
    assert hint in message


def test_unknown_plain_name_is_a_program_error_with_suggestion():
    with pytest.raises(ProgramError, match=r"lab1.py, line 3: unknown name 'cisl'; did you mean 'cislo'"):
        load("def OB1(t):\n    cislo = 1\n    t.LED = cisl > 0\n")


def test_syntax_error_names_the_line():
    with pytest.raises(ProgramError) as info:
        load("def OB1(t):\n    t.LED = = t.TLACIDLO\n")
    assert "lab1.py, line 2: syntax error" in str(info.value)
    assert "t.LED = = t.TLACIDLO" in str(info.value)


@pytest.mark.parametrize(
    ("source", "line", "words"),
    [
        pytest.param("import os\ndef OB1(t):\n    t.LED = True\n", 1, "imports", id="import"),
        pytest.param("from os import path\ndef OB1(t):\n    pass\n", 1, "imports", id="from-import"),
        pytest.param("def OB1(t):\n    f = open('x')\n", 2, "open is not available", id="open"),
        pytest.param("def OB1(t):\n    eval('1')\n", 2, "eval is not available", id="eval"),
        pytest.param("def OB1(t):\n    exec('1')\n", 2, "exec is not available", id="exec"),
        pytest.param("def OB1(t):\n    x = t.__class__\n", 2, ".__class__", id="dunder-attribute"),
        pytest.param("def OB1(t):\n    x = __builtins__\n", 2, "reserved", id="dunder-name"),
        pytest.param("class A:\n    pass\ndef OB1(t):\n    pass\n", 1, "classes", id="class"),
        pytest.param(
            "def OB1(t):\n    try:\n        t.LED = True\n    except Exception:\n        pass\n", 2, "try", id="try"
        ),
        pytest.param("X = 1\ndef OB1(t):\n    global X\n    X = 2\n", 3, "global", id="global"),
        pytest.param("def OB1(t):\n    f = lambda: 1\n", 2, "lambda", id="lambda"),
        pytest.param("def OB1(t):\n    x = [i for i in range(3)]\n", 2, "comprehensions", id="comprehension"),
        pytest.param("def OB1(t):\n    print(1)\n", 2, "print is not available", id="print"),
    ],
)
def test_subset_violations_name_the_line(source, line, words):
    with pytest.raises(SubsetError) as info:
        load(source)
    message = str(info.value)
    assert message.startswith(f"lab1.py, line {line}:")
    assert words in message


@pytest.mark.parametrize(
    ("declaration", "error", "words"),
    [
        pytest.param("Tag('%M10.8')", AddressError, "bit 8 does not exist", id="bit-8"),
        pytest.param("Tag('%M10')", AddressError, "needs a bit number", id="no-bit"),
        pytest.param("Tag('%MW10.1', Int)", AddressError, "has no bit number", id="word-with-bit"),
        pytest.param("Tag('%Z1.0')", AddressError, "not an absolute address", id="bad-area"),
        pytest.param("Tag('%Q0.0', Int)", DeclarationError, "use %QW0", id="Q-bit-typed-Int"),
        pytest.param("Tag('%MW10')", DeclarationError, "give its type", id="MW-without-type"),
        pytest.param("Tag('%MD4', Int)", DeclarationError, "use %MW4", id="MD-typed-Int"),
        pytest.param("Tag('%MB70000', Byte)", AddressError, "outside", id="outside-M"),
    ],
)
def test_bad_address_declarations(declaration, error, words):
    with pytest.raises(error, match=words):
        load(f"X = {declaration}\ndef OB1(t):\n    t.LED = True\n")


def test_two_tags_with_one_name_are_rejected():
    with pytest.raises(DeclarationError, match="'LED' is already declared"):
        load("LED = Tag('%Q0.1')\ndef OB1(t):\n    pass\n")


def test_declaration_without_a_tag_is_explained():
    with pytest.raises(DeclarationError, match=r"CISLO = Int\(\)"):
        load("CISLO = Int\ndef OB1(t):\n    pass\n")


def test_network_with_a_wrong_signature():
    with pytest.raises(ProgramError, match="exactly one parameter"):
        load("def n1():\n    pass\nOB1 = [n1]\n")


@pytest.mark.parametrize(
    ("body", "words"),
    [
        pytest.param("    t.LED = 5\n", "LED is Bool; cannot store int 5 (use True/False", id="int-into-bool"),
        pytest.param("    t.CISLO = True\n", "CISLO is Int; cannot store bool True", id="bool-into-int"),
        pytest.param("    t.CISLO = 'abc'\n", "CISLO is Int", id="text-into-int"),
        pytest.param("    t.D.R = True\n", "D.R is Real", id="bool-into-db-real"),
        pytest.param("    t.D.R = -(1)\n    t.D.B = -1\n", "D.B is Bool; cannot store int -1", id="negative-into-bool"),
    ],
)
def test_a_constant_the_tag_cannot_hold_is_refused_at_load(body, words):
    """TIA Portal refuses these when it compiles; so does plcsim, before the CPU runs, naming file and line."""
    with pytest.raises(ProgramError) as refused:
        load("CISLO = Int(0); D = DB(R=Real, B=Bool)\ndef OB1(t):\n" + body)
    message = str(refused.value)
    line = 2 + body.count("\n")
    assert message.startswith(f"lab1.py, line {line}: ") and words in message
    assert "_t" not in message


@pytest.mark.parametrize(
    ("body", "line", "words"),
    [
        pytest.param("    x = 5\n    t.LED = x\n", 4, "LED is Bool; cannot store int 5", id="int-into-bool"),
        pytest.param("    x = t.LED\n    t.CISLO = x\n", 4, "CISLO is Int; cannot store bool", id="bool-into-int"),
        pytest.param("    x = 'abc'\n    t.CISLO = x\n", 4, "CISLO is Int", id="text-into-int"),
        pytest.param("    x = True\n    t.D.R = x\n", 4, "D.R is Real", id="bool-into-db-real"),
        pytest.param("    t.T.PT = True\n", 3, "PT must be a TIME", id="bool-into-timer-preset"),
    ],
)
def test_type_mismatch_stores_stop_the_cpu_with_the_message(body, line, words):
    cpu = load("CISLO = Int(0); D = DB(R=Real); T = IEC_TIMER()\ndef OB1(t):\n" + body)
    cpu.scan()
    assert cpu.mode == "STOP"
    error = cpu.error
    assert (error.event, error.task, error.line) == ("error in the program", "OB1", line)
    assert words in error.message
    assert "_t." not in error.message  # the student's names, never the merged function's
    assert cpu.outputs["LED"] is False


def test_timer_outputs_cannot_be_written():
    with pytest.raises(ProgramError, match=r"line 3: Q of a IEC_TIMER is computed by its box.*RT"):
        load("T = IEC_TIMER()\ndef OB1(t):\n    t.T.Q = False\n")


@pytest.mark.parametrize(
    ("expression", "flagged"),
    [
        pytest.param("t.LED and P(t.TLACIDLO, 'SB')", "P(...) sits behind and/or", id="P-behind-and"),
        pytest.param("t.LED or N(t.TLACIDLO, 'SB')", "N(...) sits behind and/or", id="N-behind-or"),
        pytest.param("t.LED and t.E.R_TRIG(CLK=t.TLACIDLO)", "t.E.R_TRIG(...) sits behind", id="R_TRIG-behind-and"),
        pytest.param("P(t.TLACIDLO, 'SB') and t.LED", None, id="P-first-is-fine"),
    ],
)
def test_short_circuit_warning(expression, flagged):
    source = f"SB = Bool()\nE = R_TRIG()\nX = Bool()\ndef OB1(t):\n    t.X = {expression}\n"
    cpu = load(source)
    if flagged is None:
        assert cpu.warnings == []
    else:
        assert len(cpu.warnings) == 1
        assert cpu.warnings[0].startswith("lab1.py, line 5:") and flagged in cpu.warnings[0]


def test_short_circuit_really_skips_the_edge_instruction():
    # why the warning matters: behind `and`, P does not run while LED is FALSE and misses the edge
    source = "SB = Bool()\nX = Bool()\ndef OB1(t):\n    t.X = t.LED and P(t.TLACIDLO, 'SB')\n"
    cpu = load(source)
    cpu.set_input("TLACIDLO", True)
    cpu.scan()
    assert cpu.read("SB") is False
