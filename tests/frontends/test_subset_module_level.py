"""Hostile programs against the module level: it only declares, and nothing of it is executed.

Issue 9: a submission's module level was executed from the unrewritten tree and could assign
attributes of process-wide objects (an FB type's factory, a type's coerce), swap ``Program.source``
and from there run anything. Each class below must be refused at load time with the line, or be
harmless by construction.
"""

from __future__ import annotations

import pytest

from plcsim import CPU, Program, Tag
from plcsim.controllers.s7.instructions import IEC_TIMER
from plcsim.core.errors import ProgramError, SubsetError
from plcsim.tags.types import DTL, Int

PANEL = {"TL": Tag("%I0.0"), "LED": Tag("%Q0.0")}
NET = "def OB1(t):\n    t.LED = t.TL\n"


def load(source: str) -> CPU:
    return CPU(tags=PANEL, program=Program.from_source(source, "lab.py"))


@pytest.mark.parametrize(
    ("source", "line", "words"),
    [
        pytest.param("IEC_TIMER.factory = 1\n" + NET, 1, "this assignment at module level", id="fb-factory"),
        pytest.param("Int.coerce = 1\n" + NET, 1, "this assignment at module level", id="type-coerce"),
        pytest.param("X = Int.coerce\n" + NET, 1, "Int.coerce cannot be evaluated", id="read-attribute"),
        pytest.param(
            "X = Tag('%M0.0')\nY = X.resolved()\n" + NET, 2, "X.resolved(...) is not a declaration", id="method"
        ),
        pytest.param("for i in range(10**9):\n    pass\n" + NET, 1, "a for loop at module level", id="for-loop"),
        pytest.param("while True:\n    pass\n" + NET, 1, "a while loop at module level", id="while-loop"),
        pytest.param("if True:\n    X = Int(0)\n" + NET, 1, "an if statement at module level", id="if"),
        pytest.param("RET()\n" + NET, 1, "RET(...) is called at module level", id="ret"),
        pytest.param("MOVE(1, 'LED')\n" + NET, 1, "MOVE(...) is called at module level", id="move"),
        pytest.param("X = DIV(4, 2)\n" + NET, 1, "DIV(...) is not a declaration", id="instruction-call"),
        pytest.param("X = Int(1 + 2)\n" + NET, 1, "1 + 2 cannot be evaluated", id="arithmetic"),
        pytest.param("X, Y = Int(0), Int(0)\n" + NET, 1, "this assignment at module level", id="tuple"),
        pytest.param("X = Y = Int(0)\n" + NET, 1, "this assignment at module level", id="chain"),
        pytest.param("X = Int(0)\nX += 1\n" + NET, 2, "augmented assignment", id="augassign"),
        pytest.param("X = Int(0)\nX = Int(1)\n" + NET, 2, "already declared on line 1", id="twice"),
        pytest.param("@MAX\n" + NET, 1, "the decorator @MAX is not allowed", id="decorator"),
        pytest.param("@label\n" + NET, 1, "the decorator @label is not allowed", id="bare-label"),
        pytest.param("@label('a')\n@label('b')\n" + NET, 2, "two labels", id="two-labels"),
        pytest.param("X = DB(**{'A': Bool})\n" + NET, 1, "** unpacking", id="kwargs"),
        pytest.param("X = 'x'" + " 'y'" + "\n" + NET, None, None, id="string-constant-is-fine"),
        pytest.param("X = Int(b'1')\n" + NET, 1, "is not a PLC value", id="bytes"),
        pytest.param("X = Int(" + "'" + "x" * 20_000 + "'" + ")\n" + NET, 1, "too long", id="huge-literal"),
    ],
)
def test_module_level_admits_only_declarations(source, line, words):
    if words is None:
        load(source)
        return
    with pytest.raises(ProgramError) as info:
        load(source)
    message = str(info.value)
    assert message.startswith(f"lab.py, line {line}:"), message
    assert words in message


def test_every_refusal_lists_the_allowed_forms():
    with pytest.raises(SubsetError, match=r"a module level only declares: NAME = Int\(0\)"):
        load("X = Int(0)\nX.start = 1\n" + NET)


def test_the_shared_objects_are_untouched_after_hostile_programs():
    factory, coerce, members = IEC_TIMER.factory, Int.coerce, dict(DTL.members)
    for source in ("IEC_TIMER.factory = OB1\n", "Int.coerce = OB1\n", "X = DTL.members\n"):
        with pytest.raises(SubsetError):
            load(source + NET)
    assert IEC_TIMER.factory is factory and Int.coerce is coerce and dict(DTL.members) == members


def test_declarations_forms_the_shipped_programs_use_still_load():
    source = """
\"\"\"A docstring.\"\"\"
STEP = 10
NEG = -3
POM = Tag("%M10.0")
CISLO = Tag("%MW12", Int, retain=True)
SEEN = Int(0)
TON_A = IEC_TIMER()
C1 = IEC_COUNTER(DInt)
EDGE = R_TRIG()
NASA = UDT(OBS=Bool, POCET=Int(5))
DATA = DB(number=1, X=Bool, A=Array(0, 3, Int), S=Struct(B=Bool), N=NASA, D=DTL, TXT=String)

@label("top")
def blink(t):
    t.LED = not t.LED

def main(t):
    t.SEEN = t.SEEN + STEP + NEG

OB1 = [main]
OB30 = CyclicInterrupt([blink], period="1s", phase="0ms", priority=9)
"""
    cpu = load(source)
    cpu.scan(2)
    assert cpu.read("SEEN") == 14
    assert cpu.program.tasks["OB30"].period_ns == 1_000_000_000
    assert cpu.program.tasks["OB30"].networks[0].label == "top"


def test_a_declared_name_is_not_a_runtime_name():
    with pytest.raises(SubsetError, match=r"line 2: IEC_TIMER declares a tag or an instance"):
        load("def OB1(t):\n    x = IEC_TIMER()\n")
    with pytest.raises(SubsetError, match=r"line 2: Tag declares"):
        load("def OB1(t):\n    x = Tag('%M0.0')\n")


def test_a_constant_cannot_shadow_an_instruction():
    with pytest.raises(SubsetError, match=r"line 1: P is the name of an instruction"):
        load("P = 2\n" + NET)


def test_source_and_tree_are_read_only_and_what_runs_is_the_checked_tree():
    program = Program.from_source(NET, "lab.py")
    for attribute in ("source", "tree", "filename"):
        with pytest.raises(AttributeError):
            setattr(program, attribute, "import os\n")
    program._source = "import os\ndef OB1(t):\n    t.LED = not t.TL\n"  # even a host-side swap changes nothing
    cpu = CPU(tags=PANEL, program=program)
    cpu.set_input("TL", True)
    cpu.scan()
    assert cpu.outputs["LED"] is True


def test_module_level_code_is_never_executed_at_download():
    # a call at module level is refused, so no declaration can have side effects; only def and names run
    program = Program.from_source("SEEN = Int(0)\n" + NET, "lab.py")
    compiled_names = set(program.compile(CPU(tags=PANEL, program=program).table).code.co_names)
    assert compiled_names == {"OB1"}


def test_a_declared_tag_named_bare_in_a_network_says_write_t_name():
    with pytest.raises(SubsetError, match=r"lab.py, line 3: SEEN is a tag of the program; in a network it is t.SEEN"):
        load("SEEN = Int(0)\ndef OB1(t):\n    t.LED = SEEN > 0\n")
