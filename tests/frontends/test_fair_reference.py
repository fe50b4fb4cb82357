"""The students' instruction reference: generated from the docstrings, covering every name a program
can use, and docs/instructions.md is exactly the generated page (regenerate it with
``plcsim reference --output docs/instructions.md``)."""

from __future__ import annotations

from pathlib import Path

import pytest

from plcsim.apps.cli import main
from plcsim.core.errors import ProgramError
from plcsim.frontends.python.names import DECLARATION_NAMES, PROGRAM_NAMES
from plcsim.frontends.python.program import Program
from plcsim.frontends.python.reference import PAGE, instruction_reference, network_instructions
from plcsim.frontends.python.subset import ALLOWED_BUILTINS

ROOT = Path(__file__).parents[2]


def test_the_page_in_docs_is_the_generated_one():
    assert (ROOT / PAGE).read_text(encoding="utf-8") == instruction_reference(), (
        "docs/instructions.md is out of date: run plcsim reference --output docs/instructions.md"
    )


def test_every_name_a_program_sees_is_described():
    page = instruction_reference()
    assert PROGRAM_NAMES - set(DECLARATION_NAMES) == set(network_instructions())
    for name in PROGRAM_NAMES | (ALLOWED_BUILTINS - {"True", "False", "None"}):
        assert f"`{name}" in page or f"`t.NAME.{name}" in page, name
    assert "| `P(operand, memory)` | -\\|P\\|-: TRUE for one execution when ``operand`` went FALSE -> TRUE" in page
    assert "- `t.NAME.CTUD(CU, CD, R, LD, PV)`: Count up on CU edges and down on CD edges; returns QU." in page


def test_the_command_prints_and_writes_it(tmp_path, capsys):
    assert main(["reference"]) == 0
    assert capsys.readouterr().out == instruction_reference()
    assert main(["reference", "--output", str(tmp_path / "ref.md")]) == 0
    assert (tmp_path / "ref.md").read_text(encoding="utf-8") == instruction_reference()


def test_an_unknown_name_points_to_the_reference():
    with pytest.raises(ProgramError, match=r"unknown name 'STP'.*plcsim reference, docs/instructions\.md"):
        Program.from_source("def OB1(t):\n    STP()\n", "stop.py")
