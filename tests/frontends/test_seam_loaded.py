"""Issue 11, the front-end seam: the Python subset front end produces a LoadedProgram the CPU runs."""

from __future__ import annotations

from pathlib import Path

import pytest

from plcsim import CPU, Int, Program, Tag
from plcsim.controllers.loaded import LoadedProgram
from plcsim.core.errors import ProgramError
from plcsim.frontends import read_program

TAGS = {"TL": Tag("%I0.0"), "LED": Tag("%Q0.0"), "N": Tag("%MW10", Int)}
SOURCE = '''
def lamp(t):
    """The lamp follows the button."""
    t.LED = t.TL

def count(t):
    t.N = t.N + 1

OB1 = [lamp]
OB30 = CyclicInterrupt(count, period="10ms", phase="2ms", priority=9)
'''


def test_the_python_front_end_links_into_tasks_networks_spans_and_neutral_facts():
    cpu = CPU(tags=TAGS, program=Program.from_source(SOURCE, "lamp.py"))
    loaded = cpu.loaded
    assert isinstance(loaded, LoadedProgram) and loaded.filename == "lamp.py"
    ob1, ob30 = loaded.tasks
    assert (ob1.spec.name, ob1.spec.kind, ob1.spec.number, [n.span for n in ob1.networks]) == (
        "OB1",
        "cyclic",
        1,
        [(2, 4)],
    )
    spec = ob30.spec
    assert (spec.kind, spec.number, spec.period_ns, spec.phase_ns, spec.priority) == (
        "interrupt",
        30,
        10**7,
        2 * 10**6,
        9,
    )
    assert ob30.tags_used == {"N"} and [n.span for n in ob30.networks] == [(6, 7)]
    assert loaded.facts.tags_read == {"TL", "N"} and loaded.facts.tags_written == {"LED", "N"}
    cpu.run("25ms")
    assert cpu.t.N == 3  # at 2, 12 and 22 ms


def test_a_program_file_is_read_by_the_front_end_its_suffix_names(tmp_path: Path):
    (tmp_path / "led.py").write_text("def OB1(t):\n    t.LED = t.TL\n", encoding="utf-8")
    program = read_program(tmp_path / "led.py")
    assert isinstance(program, Program) and program.filename == str(tmp_path / "led.py")
    with pytest.raises(ProgramError, match=r"led\.txt: no front end reads \.txt; use \.il, \.mech, \.py"):
        read_program(tmp_path / "led.txt")


def test_a_program_downloaded_again_to_an_equal_table_reuses_its_compilation_and_no_more():
    """A grade downloads one program once per scenario: the second download of an equal table reuses the
    code (each gets its own warnings and timer set); another table or option compiles anew."""
    from exercises import get

    exercise = get("4.3.17")  # a data block, whose type is built with the exercise's table
    program = exercise.reference.program()
    first, again = (program.declare_into(exercise.tag_table()) for _ in range(2))
    a, b = program.compile(first), program.compile(again)
    assert b.code is a.code and b.analysis is a.analysis
    assert b.warnings == a.warnings and b.warnings is not a.warnings and b.inert_timers is not a.inert_timers
    assert program.compile(first, input_writes="error").code is not a.code
    other = program.declare_into(exercise.tag_table())
    other.add("EXTRA", Tag("%M90.0"), source="test")
    assert program.compile(other).code is not a.code
    assert exercise.tag_table() is not exercise.tag_table()  # each caller may add to its own copy
    assert exercise.tag_table().entries["DATA"] is exercise.tag_table().entries["DATA"]
