"""Mutation testing of Tecomat instruction-list references (plcsim.mutate.il): each operator's exact
mutated line, what is left alone, and the grading of T-01's, T-02's and T-06's mutants on one seed."""

from __future__ import annotations

import dataclasses
import json

import pytest

from exercises import get
from plcsim.apps.cli import main
from plcsim.core.errors import PlcError
from plcsim.exercise.model import Solution
from plcsim.mutate.engine import EQUIVALENT, EXPLAINED, KILLED, STILLBORN, exercise_mutants, mutate_exercise
from plcsim.mutate.il import derive_il_mutants
from plcsim.mutate.mutant import Mutant


def changed(original: str, mutant: Mutant) -> dict[int, str]:
    """The mutant's changed lines: line number -> new text."""
    old, new = original.splitlines(), mutant.source.splitlines()
    assert len(old) == len(new), "a mutant keeps every line in its place"
    return {k: b for k, (a, b) in enumerate(zip(old, new, strict=True), 1) if a != b}


def mutants_of(text: str, operator: str) -> list[tuple[str, dict[int, str]]]:
    return [(str(m), changed(text, m)) for m in derive_il_mutants(text) if m.operator == operator]


@pytest.mark.parametrize(
    ("line", "label", "new"),
    [
        ("LD  START   ; START", "LD START → LDC START", "LDC  START   ; START"),
        ("ldc x0.1", "ldc x0.1 → ld x0.1", "ld x0.1"),
        ("ANC STOP", "ANC STOP → AND STOP", "AND STOP"),
        ("and k1", "and k1 → anc k1", "anc k1"),
        ("OR MOTOR", "OR MOTOR → ORC MOTOR", "ORC MOTOR"),
        ("ORC x0.2", "ORC x0.2 → OR x0.2", "OR x0.2"),
        ("XOR x0.2", "XOR x0.2 → XOC x0.2", "XOC x0.2"),
        ("WR  MOTOR", "WR MOTOR → WRC MOTOR", "WRC  MOTOR"),
    ],
)
def test_a_contact_is_negated_in_the_case_it_is_written_in(line, label, new):
    text = f"LD x0.0\n{line}\n"
    assert mutants_of(text, "negate")[-1] == (f"line 2: {label}", {2: new})


def test_a_number_is_no_contact_to_negate():
    text = "#def zpozdeni 25\nLD 45\nLD zpozdeni\nAND %111\nWR y0.0\n"
    assert [m for m, _ in mutants_of(text, "negate")] == ["line 5: WR y0.0 → WRC y0.0"]


def test_set_for_reset_and_a_series_contact_for_a_parallel_one():
    text = "ld k5\nres em1\nAND x0.1\nanc x0.2\nOR\n"
    assert mutants_of(text, "set-reset") == [("line 2: res em1 → set em1", {2: "set em1"})]
    assert mutants_of(text, "and-or") == [
        ("line 3: AND x0.1 → OR x0.1", {3: "OR x0.1"}),
        ("line 4: anc x0.2 → orc x0.2", {4: "orc x0.2"}),
        ("line 5: OR → AND", {5: "AND"}),
    ]


def test_a_timer_kind_for_another_and_its_time_base_one_step_off():
    text = "#reg word casovac\nld x0.0\nld 25\nton casovac.0   ; 250 ms\nwr y0.0\n"
    assert mutants_of(text, "timer") == [
        ("line 4: ton casovac.0 → tof casovac.0", {4: "tof casovac.0   ; 250 ms"}),
        ("line 4: ton casovac.0 → imp casovac.0", {4: "imp casovac.0   ; 250 ms"}),
    ]
    assert mutants_of(text, "time-base") == [("line 4: ton casovac.0 → ton casovac.1", {4: "ton casovac.1   ; 250 ms"})]


def test_a_comparison_at_its_boundary_and_the_flags_less_for_less_or_equal():
    text = "LD RW0\nGT 4\nLD RW2\nLT $0A\nLD S0.1\n"
    assert mutants_of(text, "boundary") == [
        ("line 2: GT 4 → GT 3", {2: "GT 3"}),  # > 4 read as >= 4
        ("line 4: LT $0A → LT $0B", {4: "LT $0B"}),  # < 10 read as <= 10
        ("line 5: LD S0.1 → LD S0.2", {5: "LD S0.2"}),
    ]


def test_a_constant_moves_a_tenth_of_its_magnitude_in_its_own_notation():
    text = "#def zpozdeni 25   ; 25 units\n#def vstup x0.0\nLD 1\nLD %0011\nEQ 300\n"
    assert mutants_of(text, "constant") == [
        ("line 1: #def zpozdeni 25 → 24", {1: "#def zpozdeni 24   ; 25 units"}),
        ("line 1: #def zpozdeni 25 → 26", {1: "#def zpozdeni 26   ; 25 units"}),
        ("line 3: LD 1 → LD 0", {3: "LD 0"}),
        ("line 3: LD 1 → LD 2", {3: "LD 2"}),
        ("line 4: LD %0011 → LD %0010", {4: "LD %0010"}),
        ("line 4: LD %0011 → LD %0100", {4: "LD %0100"}),
        ("line 5: EQ 300 → EQ 290", {5: "EQ 290"}),
        ("line 5: EQ 300 → EQ 310", {5: "EQ 310"}),
    ]


def test_a_dropped_instruction_keeps_its_label_and_comment():
    text = "P 0\nkonec: LD x0.0 ; the end\nWR y0.0\nE 0\n"
    assert mutants_of(text, "drop") == [
        ("line 2: LD x0.0 dropped", {2: "konec: ; the end"}),
        ("line 3: WR y0.0 dropped", {3: ""}),
    ]


def test_a_swap_exchanges_two_instructions_of_one_process_and_keeps_their_comments():
    text = "P 0\nLD x0.0 ; a\n; between\nWR y0.0 ; b\nE 0\nP 1\nLD x0.1\nlab: WR y0.1\nWR y0.2\nL 3\nWR y0.3\nE 1\n"
    assert mutants_of(text, "swap") == [
        ("line 2: LD x0.0 ⇄ WR y0.0 (lines 2 and 4)", {2: "WR y0.0 ; a", 4: "LD x0.0 ; b"}),
        ("line 8: WR y0.1 ⇄ WR y0.2 (lines 8 and 9)", {8: "lab: WR y0.2", 9: "WR y0.1"}),
    ]  # nothing moves across P/E or a label: 'LD x0.1' and 'lab: WR y0.1' stay apart, and so do y0.2 and y0.3


def test_mutants_with_the_text_of_an_earlier_one_are_left_out():
    text = "LD RW0\nGT 4\nWR y0.0\nWR y0.0\n"
    mutants = derive_il_mutants(text)
    assert [(m.operator, str(m)) for m in mutants if m.line == 2] == [
        ("boundary", "line 2: GT 4 → GT 3"),  # the constant step down writes the same line: left out
        ("constant", "line 2: GT 4 → GT 5"),
        ("drop", "line 2: GT 4 dropped"),
        ("swap", "line 2: GT 4 ⇄ WR y0.0 (lines 2 and 3)"),
    ]
    assert not any(m.operator == "swap" and m.line == 3 for m in mutants)  # the same two lines: the original
    assert len({m.source for m in mutants} | {text}) == len(mutants) + 1
    assert [m.number for m in mutants] == list(range(1, len(mutants) + 1))


def test_directives_comments_and_processes_are_left_alone():
    text = "; motor\n#program motor\n#def START x0.0\n#reg word w\nP 0\nLD START\nE 0\n"
    assert [(str(m), changed(text, m)) for m in derive_il_mutants(text)] == [
        ("line 6: LD START → LDC START", {6: "LDC START"}),
        ("line 6: LD START dropped", {6: ""}),
    ]


def test_the_t01_reference_has_the_stop_contact_negated_among_its_mutants():
    labels = [str(m) for m in exercise_mutants(get("t-01"))]
    assert "line 7: ANC STOP → AND STOP" in labels
    assert "line 5: LD START dropped: a forgotten contact, OR MOTOR → LD MOTOR" in labels
    assert len(labels) == 14


def test_t01_mutants_are_killed_by_the_check_that_explains_them():
    exercise = get("t-01")
    chosen = [m for m in exercise_mutants(exercise) if m.number in (6, 7, 9)]
    assert [m.description for m in chosen] == [
        "OR MOTOR → AND MOTOR",
        "OR MOTOR dropped: a forgotten contact",
        "ANC STOP → AND STOP",
    ]
    report = mutate_exercise(exercise, seeds=1, mutants=chosen)
    assert report.reference_failures == []
    assert [o.status for o in report.outcomes] == [KILLED] * 3
    assert "releasing START leaves the motor running" in report.outcomes[1].detail
    assert "START alone switches the motor on" in report.outcomes[2].detail
    assert report.score == 1.0


def test_an_il_mutant_that_does_not_assemble_is_stillborn():
    broken = Mutant(1, "drop", 2, "a slip", "LD START\nWX MOTOR\n")
    report = mutate_exercise(get("t-01"), seeds=1, mutants=[broken])
    assert report.outcomes[0].status == STILLBORN
    assert "<mutant 1>, line 2, column 1: no instruction 'WX'; did you mean WR?" in report.outcomes[0].detail
    assert report.score is None


def test_a_commutative_swap_is_equivalent_though_the_mutant_has_another_file_name():
    exercise = get("t-06")  # its reference's #include warning names the file: a name is not behaviour
    swap = [m for m in exercise_mutants(exercise) if m.description.startswith("and start2 ⇄ and k1")]
    report = mutate_exercise(exercise, seeds=1, mutants=swap)
    assert [o.status for o in report.outcomes] == [EQUIVALENT]


def test_t02s_preset_one_unit_longer_is_explained_by_the_manuals_tolerance():
    exercise = get("t-02")
    longer = [m for m in exercise_mutants(exercise) if m.description == "#def zpozdeni 25 → 26"]
    report = mutate_exercise(exercise, seeds=1, mutants=longer)
    assert [o.status for o in report.outcomes] == [EXPLAINED]
    assert "±1 unit" in report.outcomes[0].reason


def test_a_reference_in_another_language_is_refused_with_the_reason(tmp_path):
    exercise = get("t-01")
    program = tmp_path / "reference.st"
    program.write_text("MOTOR := (START OR MOTOR) AND NOT STOP;\n", encoding="utf-8")
    other = dataclasses.replace(exercise, solutions=[Solution("reference", program)])
    with pytest.raises(PlcError, match=r"T-01: its reference reference\.st is neither a Python \(S7\) nor an "):
        exercise_mutants(other)


def test_the_cli_mutates_a_tecomat_exercise(tmp_path, capsys):
    out = tmp_path / "t01.json"
    assert main(["mutate", "t-01", "--seeds", "1", "--json", str(out)]) == 0
    assert "mutation score: 100 %" in capsys.readouterr().out
    data = json.loads(out.read_text(encoding="utf-8"))
    assert data["counts"] == {"killed": 14, "survived": 0, "explained": 0, "equivalent": 0, "stillborn": 0}
    assert data["outcomes"][8]["mutant"]["label"] == "line 7: ANC STOP → AND STOP"
