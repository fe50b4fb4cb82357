"""Issue 11, what a student reads: an undeclared edge memory bit says to declare it, and a name near an
instance's box (``TONN``, ``ctu``) says which box it is and how it is called."""

from __future__ import annotations

import re

import pytest

from plcsim import CPU, Tag
from plcsim.core.errors import ProgramError

TAGS = {"TL": Tag("%I0.0"), "LED": Tag("%Q0.0"), "SB1": Tag("%M0.0")}


@pytest.mark.parametrize(
    ("bit", "expected"),
    [
        (
            "M1",
            r"'M1' is not declared: declare it in the program \(M1 = Bool\(\)\) or in the tag table \(a %M bit\)$",
        ),
        ("SB2", r"'SB2' is not declared: .*\(a %M bit\); did you mean 'SB1'\?"),
    ],
)
def test_an_undeclared_edge_memory_bit_says_to_declare_it(bit: str, expected: str):
    cpu = CPU(tags=TAGS, program=f'def OB1(t):\n    if P(t.TL, "{bit}"):\n        t.LED = True\n')
    cpu.set_input("TL", True)
    cpu.scan()
    assert cpu.mode == "STOP" and cpu.error.line == 2
    assert cpu.error.message.startswith("OB1 network 1 (OB1), line 2: the edge memory bit")
    assert re.search(expected, cpu.error.message)


@pytest.mark.parametrize(
    ("source", "expected"),
    [
        (
            'def OB1(t):\n    t.LED = TONN(IN=t.TL, PT="1s")\n',
            "line 2: unknown name 'TONN'; TON is a box of an IEC_TIMER "
            "instance: declare TIMER = IEC_TIMER() and call t.TIMER.TON(IN=..., PT=...)",
        ),
        (
            "def OB1(t):\n    t.LED = ctu(CU=t.TL)\n",
            "unknown name 'ctu'; CTU is a box of an IEC_COUNTER instance: "
            "declare COUNTER = IEC_COUNTER() and call t.COUNTER.CTU(CU=..., R=..., PV=...)",
        ),
        (
            "def OB1(t):\n    t.LED = f_trigg(CLK=t.TL)\n",
            "F_TRIG is a box of an F_TRIG instance: declare EDGE = F_TRIG() and call t.EDGE.F_TRIG(CLK=...)",
        ),
        ("T1 = TONN()\n\ndef OB1(t):\n    t.LED = t.TL\n", "line 1: unknown name 'TONN'; TON is a box of an IEC_TIMER"),
    ],
)
def test_a_name_near_a_box_says_which_instance_it_belongs_to(source: str, expected: str):
    with pytest.raises(ProgramError) as caught:
        CPU(tags=TAGS, program=source)
    assert expected in str(caught.value)


def test_a_name_near_nothing_gets_no_box_hint():
    with pytest.raises(ProgramError) as caught:
        CPU(tags=TAGS, program="def OB1(t):\n    t.LED = LAMP\n")
    assert "box" not in str(caught.value)
