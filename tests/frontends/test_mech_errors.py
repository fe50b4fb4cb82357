"""The ``.mech`` front end's errors: each names the file, the line and the fix, in the student's names."""

from __future__ import annotations

from pathlib import Path

import pytest

from plcsim import CPU, Tag
from plcsim.core.errors import ProgramError, UnknownTagError
from plcsim.frontends import read_program
from plcsim.frontends.mech import MechProgram

TAGS = {"A": Tag("%I0.0"), "KONTAKT1": Tag("%I0.1"), "LED": Tag("%Q0.0")}


@pytest.mark.parametrize(
    ("text", "message"),
    [
        ("LDR A\nLDX A\n", r"lab\.mech, line 2: LDX is not an instruction of the PLC836 subset; use LDR, LO"),
        ("LDR KONTAKT 1\n", r"line 1: operand 'KONTAKT 1' has a space in it; a name is one word: KONTAKT1"),
        ("LDR A\nEX0\n", r"line 2: EX0 outside a mechanism; EX-type instructions belong between MECH_BEGIN"),
        ("MECH_BEGIN M\nEX\nMECH_END N\n", r"line 3: MECH_END N closes mechanism M; write MECH_END M"),
        ("MECH_BEGIN M\nEX\n", r"line 1: mechanism M has no end; write MECH_END M after it"),
        ("MECH_BEGIN M\nMECH_BEGIN N\n", r"line 2: MECH_BEGIN N inside mechanism M; close it with MECH_END M"),
        ("TEX0 A\n", r"line 1: 'TEX0 A': write TEX0 COUNTER,TIME,LABEL\[,ERROR\]"),
        (
            "MECH_BEGIN M\nLDR A\nTEX0 WORD.CITAC,50,ERR\nERR:\nMECH_END M\n",
            r"line 3: WORD\.CITAC types both operands, so the time '50' must be an address such as \(REKONFIG\+14\), "
            r"not a constant; drop the WORD\. prefix",
        ),
        ("X: LDR A\nX: WR LED\n", r"line 2: label X is defined twice"),
        ("LDR A\nEND:\n", r"line 2: label END names no instruction; put one after it"),
        ("EQUI D1,fifty\n", r"line 1: write EQUI NAME,VALUE with a number such as 50 or 12H"),
    ],
)
def test_a_mistake_in_the_text_names_the_line_and_the_fix(text, message):
    with pytest.raises(ProgramError, match=message):
        MechProgram(text, "lab.mech")


@pytest.mark.parametrize(
    ("text", "error", "message"),
    [
        ("LDR AA\nWR LED\n", UnknownTagError, r"lab\.mech, line 1: no bit 'AA'; did you mean 'A'\?"),
        ("MECH_BEGIN M\nJUM NOPE\nMECH_END M\n", ProgramError, r"line 2: no label NOPE; write 'NOPE:' before"),
        (
            "LDR A\nJUM IN\nMECH_BEGIN M\nIN: EX\nMECH_END M\n",
            ProgramError,
            r"line 2: label IN lies outside the code outside mechanisms; a jump stays inside it",
        ),
        ("FL 2,LED\n", ProgramError, r"line 1: FL sets a bit to 0 or 1: write FL 1,LED or FL 0,LED"),
        ("LDR A\nWR -LED\n", ProgramError, r"line 2: WR writes a bit; write WR LED"),
        ("LOD 5\nSTO LED\n", ProgramError, r"line 2: STO stores the number in DR; LED is a bit"),
        ("MECH_INIT MM\n", UnknownTagError, r"line 1: no mechanism 'MM'"),
    ],
)
def test_a_name_or_label_that_does_not_fit_is_named_when_the_program_is_loaded(text, error, message):
    with pytest.raises(error, match=message):
        CPU(tags=TAGS, program=MechProgram(text, "lab.mech"))


def test_a_mech_file_is_read_by_its_suffix_and_its_errors_name_the_file(tmp_path: Path):
    (tmp_path / "lamp.mech").write_text("LDR A\nWR LED\n", encoding="utf-8")
    assert isinstance(read_program(tmp_path / "lamp.mech"), MechProgram)
    (tmp_path / "bad.mech").write_text("; a lamp\nLDR A\nWRR LED\n", encoding="utf-8")
    with pytest.raises(ProgramError, match=r"bad\.mech, line 3: WRR is not an instruction"):
        read_program(tmp_path / "bad.mech")


def test_a_loop_without_a_state_is_stopped_by_the_cycle_watchdog():
    cpu = CPU(tags=TAGS, program=MechProgram("MECH_BEGIN M\nL: LDR A\nJUM L\nMECH_END M\n", "loop.mech"))
    cpu.write("M.ACTIVE", True)
    cpu.scan()
    assert cpu.mode == "STOP" and "watchdog" in cpu.error.message.lower()
