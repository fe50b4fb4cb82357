"""The rungs read from a program: the shapes the course draws, and a text box wherever a rung could not
be faithful (an instruction with an effect that Python skips, a loop); a wrong drawing is caught."""

from __future__ import annotations

from dataclasses import replace

import pytest
from faithful import run_side_by_side

from exercises import get
from plcsim import CPU, Int, Tag
from plcsim.frontends.python.program import Program
from plcsim.ladder import build_ladder
from plcsim.ladder.model import Box, Compare, Contact, Fork, Invert, Operation, Parallel, Rung, Series, TextBox
from plcsim.ladder.semantics import ladder_source

TAGS = {
    "S1": Tag("%I0.0"),
    "S2": Tag("%I0.1"),
    "S3": Tag("%I0.2"),
    "D1": Tag("%Q0.0"),
    "D2": Tag("%Q0.1"),
    "N": Tag("%MW10", Int),
}


def network(source: str, name: str = "OB1"):
    blocks = build_ladder(Program.from_source(source), _table())
    return next(n for b in blocks for n in b.networks if n.name == name)


def _table():
    from plcsim.tags import TagTable

    table = TagTable()
    for name, tag in TAGS.items():
        table.add(name, tag)
    return table


def kinds(series: Series) -> list[str]:
    return [type(item).__name__ + (f":{item.kind}" if hasattr(item, "kind") else "") for item in series.items]


def test_a_latch_is_a_parallel_branch_in_series_with_an_nc_contact_and_a_coil():
    net = network("def OB1(t):\n    t.D1 = (t.S1 or t.D1) and not t.S2\n")
    (rung,) = net.rungs
    assert kinds(rung.series) == ["Parallel", "Contact:NC", "Coil:="]
    parallel = rung.series.items[0]
    assert [[c.operand for c in b.items] for b in parallel.branches] == [['"S1"'], ['"D1"']]


def test_not_over_a_group_becomes_nc_contacts_by_de_morgan_and_a_compare_an_inverted_group():
    (rung,) = network("def OB1(t):\n    t.D1 = not (t.S1 or t.S2)\n").rungs
    assert kinds(rung.series) == ["Contact:NC", "Contact:NC", "Coil:="]
    (rung,) = network("def OB1(t):\n    t.D1 = not (t.S1 and t.S2)\n").rungs
    assert kinds(rung.series) == ["Parallel", "Coil:="]
    (rung,) = network("def OB1(t):\n    t.D1 = t.S1 and not t.N >= 3\n").rungs
    assert isinstance(rung.series.items[1], Invert) and isinstance(rung.series.items[1].inner.items[0], Compare)


def test_an_if_with_constant_stores_is_a_fork_of_set_and_reset_coils():
    (rung,) = network("def OB1(t):\n    if t.S1:\n        t.D1 = True\n        t.D2 = False\n        t.N = 5\n").rungs
    contact, fork = rung.series.items
    assert isinstance(contact, Contact) and isinstance(fork, Fork)
    outputs = [b.items[-1] for b in fork.branches]
    assert [(o.kind, o.operand) for o in outputs[:2]] == [("S", '"D1"'), ("R", '"D2"')]
    assert isinstance(outputs[2], Operation) and outputs[2].name == "MOVE" and outputs[2].outputs == (("OUT1", '"N"'),)


def test_a_timer_box_sits_in_the_rung_with_its_in_contacts_before_it_and_pt_at_its_pin():
    net = network(
        'T = IEC_TIMER()\n\ndef OB1(t):\n    if t.T.TON(IN=t.S1 and not t.S2, PT="10s"):\n        t.D1 = True\n'
    )
    (rung,) = net.rungs
    assert kinds(rung.series) == ["Contact:NO", "Contact:NC", "Box", "Coil:S"]
    box = rung.series.items[2]
    assert isinstance(box, Box) and box.instance == '"T"' and box.rung_pin == "IN"
    assert [(p, v) for p, v, _ in box.pins] == [("PT", "T#10s")] and "ET" in box.outputs


@pytest.mark.parametrize(
    ("source", "why"),
    [
        ('def OB1(t):\n    t.D1 = t.S1 and P(t.S2, "M1")\n', "behind and/or"),
        ('T = IEC_TIMER()\n\ndef OB1(t):\n    if t.S1:\n        t.T.TON(IN=t.S2, PT="1s")\n', "under a condition"),
        ('T = IEC_TIMER()\n\ndef OB1(t):\n    t.D1 = t.S1 or t.T.TON(IN=t.S2, PT="1s")\n', "behind and/or"),
        ("def OB1(t):\n    for i in range(3):\n        t.N = t.N + i\n", "for statement"),
        ("def OB1(t):\n    if t.S1:\n        t.D1 = True\n    else:\n        t.D2 = True\n", "else"),
    ],
)
def test_what_has_no_faithful_rung_is_a_text_box_of_the_program_s_own_lines(source, why):
    net = network(source)
    (box,) = net.text_boxes
    assert why in box.reason
    assert box.text.splitlines()[0] in source


def test_an_edge_contact_first_in_its_rung_is_drawn_with_its_memory_bit():
    (rung,) = network('def OB1(t):\n    t.D1 = P(t.S1, "M_S1") and t.S2\n').rungs
    edge = rung.series.items[0]
    assert (edge.kind, edge.operand, edge.memory) == ("P", '"S1"', '"M_S1"')


def test_a_wrong_drawing_is_caught_by_the_side_by_side_run():
    """The proof can fail: the 4.3.7 reference with one contact of its reset rung drawn NC instead of NO."""
    exercise = get("4.3.7")
    program = exercise.reference.program()
    blocks = build_ladder(program, exercise.tag_table())
    net = blocks[0].networks[2]  # stop_belt: S2 OR TON_A.Q OR ALARM resets D1
    rung = net.parts[0]
    assert isinstance(rung, Rung) and isinstance(rung.series.items[0], Parallel)
    parallel = rung.series.items[0]
    first = parallel.branches[0].items[0]
    wrong = replace(parallel, branches=(Series((replace(first, kind="NC"),)), *parallel.branches[1:]))
    net.parts[0] = replace(rung, series=Series((wrong, *rung.series.items[1:])))
    drawn = Program(ladder_source(program, blocks), "drawn.py")
    original_cpu = CPU(exercise.tag_table(), program)
    drawn_cpu = CPU(exercise.tag_table(), drawn)
    with pytest.raises(AssertionError, match="after network stop_belt"):
        run_side_by_side(original_cpu, drawn_cpu, [({"S1": True, "S2": False}, 0)])


def test_text_boxes_run_as_written_and_the_title_and_comment_come_from_the_docstring():
    source = (
        'def OB1(t):\n    """Counting\n\n    adds S1 three times."""\n    for i in range(3):\n        t.N = t.N + 1\n'
    )
    net = network(source)
    assert (net.title, net.comment) == ("Counting", "adds S1 three times.")
    assert isinstance(net.parts[0], TextBox)
    assert "for i in range(3):" in ladder_source(
        Program.from_source(source), build_ladder(Program.from_source(source), _table())
    )
