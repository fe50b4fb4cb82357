"""Mutation testing of the checks (plcsim.mutate): the Python operators, kill / survive / equivalent, the CLI.

The full sweep over every exercise is the benchmark ``python -m benchmarks --only mutation``; these
tests use the smallest exercises and one seed.
"""

from __future__ import annotations

import dataclasses
import json
import re
from pathlib import Path

import pytest
from rich.console import Console

from exercises import all_exercises, get
from plcsim.apps.cli import main
from plcsim.core.errors import ExerciseError
from plcsim.frontends.python.program import Program
from plcsim.grading.grader import grade
from plcsim.mutate import engine, python
from plcsim.mutate.engine import (
    EQUIVALENT,
    EXPLAINED,
    KILLED,
    STILLBORN,
    SURVIVED,
    MutationReport,
    Outcome,
    behaviour,
    declared_equivalents,
    edge_memories,
    exercise_mutants,
    mutate_exercise,
    print_mutation_report,
)
from plcsim.mutate.mutant import Mutant
from plcsim.mutate.python import derive_mutants
from plcsim.tags.table import Tag, TagTable
from plcsim.tags.types import Int

SMALL = """T = IEC_TIMER()


def start(t):
    if P(t.S1, "M1") and not t.S2:
        t.D1 = True


def stop(t):
    t.T.TON(IN=t.D1, PT="10s")
    if t.T.Q or t.CNT > 5:
        t.D1 = False
    if t.S1:
        t.LED = True


OB1 = [start, stop]
"""


def small_table() -> TagTable:
    table = TagTable()
    table.add("S1", Tag("%I0.0"))
    table.add("S2", Tag("%I0.1"))  # wired NC
    table.add("D1", Tag("%Q0.0"))
    table.add("LED", Tag("%Q0.1"))
    table.add("CNT", Tag("%MW10", Int))
    return table


def test_the_operators_give_the_expected_mutants_of_a_small_program():
    mutants = derive_mutants(SMALL, small_table(), nc_inputs=["S2"])
    assert [(m.operator, str(m)) for m in mutants] == [
        ("nc-as-no", "line 5: NC input S2 read as NO: every read negated (line 5)"),
        ("negate", "line 5: t.S1 → not t.S1"),
        ("and-or", "line 5: P(t.S1, 'M1') and (not t.S2) → P(t.S1, 'M1') or not t.S2"),
        ("drop-operand", "line 5: P(t.S1, 'M1') and (not t.S2) → not t.S2"),
        ("negate-operand", "line 5: P(t.S1, 'M1') and (not t.S2) → not P(t.S1, 'M1') and (not t.S2)"),
        ("drop-operand", "line 5: P(t.S1, 'M1') and (not t.S2) → P(t.S1, 'M1')"),
        ("edge", "line 5: P(t.S1, 'M1') → t.S1"),
        ("edge-kind", "line 5: P(t.S1, 'M1') → N(t.S1, 'M1')"),
        ("coil", "line 6: t.D1 = True → t.D1 = False"),
        ("negate", "line 10: t.D1 → not t.D1"),
        ("timer", "line 10: t.T: TON → TOF"),
        ("timer", "line 10: t.T: TON → TP"),
        ("preset", "line 10: PT '10s' → '9s'"),
        ("preset", "line 10: PT '10s' → '11s'"),
        ("drop", "line 10: statement dropped: t.T.TON(IN=t.D1, PT='10s')"),
        ("negate", "line 11: t.T.Q → not t.T.Q"),
        ("and-or", "line 11: t.T.Q or t.CNT > 5 → t.T.Q and t.CNT > 5"),
        ("drop-operand", "line 11: t.T.Q or t.CNT > 5 → t.CNT > 5"),
        ("drop-operand", "line 11: t.T.Q or t.CNT > 5 → t.T.Q"),
        ("negate-operand", "line 11: t.T.Q or t.CNT > 5 → t.T.Q or not t.CNT > 5"),
        ("boundary", "line 11: t.CNT > 5 → t.CNT >= 5"),
        ("preset", "line 11: t.CNT > 5 → t.CNT > 4"),
        ("preset", "line 11: t.CNT > 5 → t.CNT > 6"),
        ("swap", "line 11: if-blocks at lines 11 and 13 swapped"),
        ("drop", "line 11: statement dropped: if t.T.Q or t.CNT > 5:"),
        ("coil", "line 12: t.D1 = False → t.D1 = True"),
        ("negate", "line 13: t.S1 → not t.S1"),
        ("drop", "line 13: statement dropped: if t.S1:"),
        ("coil", "line 14: t.LED = True → t.LED = False"),
        ("swap", "line 17: OB1: networks start and stop swapped"),
        ("drop", "line 17: OB1: network start dropped"),
        ("drop", "line 17: OB1: network stop dropped"),
    ]
    assert [m.number for m in mutants] == list(range(1, len(mutants) + 1))
    # Int reads (t.CNT) are never negated (their comparison is), and no mutant repeats the original or another.
    sources = [m.source for m in mutants]
    assert len(set(sources)) == len(sources)
    assert not any(re.search(r"not t\.CNT(?! >)", s) for s in sources)
    assert sum("not t.CNT > 5" in s for s in sources) == 1


def test_a_forgotten_interlock_is_a_mutant_of_the_reference():
    """6.3.3's stroke started without the KS1 test (the shipped wrong-no-ks1-interlock) is one of the reference's
    drop-operand mutants, and an operand of three left out keeps the other two in series."""
    exercise = get("6.3.3")
    wrong = exercise.solution("wrong-no-ks1-interlock").path.read_text(encoding="utf-8")
    dropped = [m for m in python.reference_mutants(exercise) if m.operator == "drop-operand"]
    assert [m.description.split(" → ")[1] for m in dropped] == [
        "t.KS1 and (not t.OBJEKT_BOL_DOLE)",
        "not t.OS2 and (not t.OBJEKT_BOL_DOLE)",
        "not t.OS2 and t.KS1",
    ]
    assert "if not t.OS2 and (not t.OBJEKT_BOL_DOLE):" in dropped[1].source
    assert "if not t.OS2 and not t.OBJEKT_BOL_DOLE:" in wrong


def test_the_timer_and_edge_boxes_swapped_are_those_of_the_s7_instruction_descriptions():
    assert python._TIMERS == ("TON", "TOF", "TP")  # TONR's reset R makes it no slip for these
    assert python._EDGE_BOXES == {"R_TRIG": "F_TRIG", "F_TRIG": "R_TRIG"}


def test_a_mutant_is_the_program_with_one_change_and_still_loads():
    by_label = {str(m): m for m in derive_mutants(SMALL, small_table(), nc_inputs=["S2"])}
    timer = by_label["line 10: t.T: TON → TOF"].source
    assert "t.T.TOF(IN=t.D1, PT='10s')" in timer and "TON" not in timer
    nc = by_label["line 5: NC input S2 read as NO: every read negated (line 5)"].source
    assert "if P(t.S1, 'M1') and t.S2:" in nc
    swapped = by_label["line 17: OB1: networks start and stop swapped"].source
    assert swapped.rstrip().endswith("OB1 = [stop, start]")
    for mutant in by_label.values():
        Program(mutant.source, "<mutant>")  # parses and passes the subset check


def test_every_read_of_an_nc_input_is_negated_at_once():
    mutants = exercise_mutants(get("4.3.10"))  # four NC light barriers
    nc = [m for m in mutants if m.operator == "nc-as-no"]
    assert [m.description for m in nc][-1] == "NC input D2_OS2 read as NO: every read negated (lines 34, 41)"
    assert "if t.D2_VPRED and (not t.DATA.D2_POZ2_OBS) and t.D2_OS2:" in nc[-1].source
    assert "if not t.D2_VPRED and (not t.D2_OS2):" in nc[-1].source


def test_a_negated_contact_is_killed_by_the_check_that_reads_it():
    report = mutate_exercise(get("4.3.1"), seeds=1)
    assert [(o.mutant.description, o.status) for o in report.outcomes] == [("t.TLACIDLO → not t.TLACIDLO", KILLED)]
    assert "LED equals the button in every scan" in report.outcomes[0].detail
    assert report.score == 1.0


def test_a_preset_hidden_by_a_slow_task_is_equivalent_and_leaves_the_score():
    exercise = get("4.3.21")  # TON 100 ms looked at once a second by OB30: 90 ms cannot be told apart
    mutant = next(m for m in exercise_mutants(exercise) if m.description == "PT '100ms' → '90ms'")
    report = mutate_exercise(exercise, seeds=1, mutants=[mutant])
    assert report.outcomes[0].status == EQUIVALENT
    assert report.score is None
    # Equivalent at the exercise's tags, not in every column: the timer's own ET stops at 90 ms.
    sims = [
        exercise.simulation(p, exercise.scenarios[0], seed=1)
        for p in (exercise.reference.program(), Program(mutant.source, "<m>"))
    ]
    for sim in sims:
        sim.run()
    assert sims[0].trace.digest() != sims[1].trace.digest()
    assert behaviour(exercise, sims[0].trace) == behaviour(exercise, sims[1].trace)


def test_a_correct_variant_survives_and_is_not_called_equivalent():
    # 4.3.11 without its declaration: the falling edge of Clock_1Hz is also a 1-s pulse, half a second later
    exercise = dataclasses.replace(get("4.3.11"), spec_equivalent={})
    report = mutate_exercise(exercise, seeds=1)
    assert [(o.mutant.description, o.status) for o in report.outcomes] == [
        ("P(t.Clock_1Hz, 'AUX') → t.Clock_1Hz", KILLED),
        ("P(t.Clock_1Hz, 'AUX') → N(t.Clock_1Hz, 'AUX')", SURVIVED),
    ]
    assert report.score == 0.5
    assert "these differ: Takt1s (seed 1" in report.outcomes[1].detail
    console = Console(record=True, width=200)
    print_mutation_report(report, console)
    text = console.export_text()
    assert "surviving mutants" in text and "N(t.Clock_1Hz, 'AUX')" in text and "mutation score: 50 %" in text
    assert "every check passes, but these differ: Takt1s (seed 1" in text


def test_a_survivor_the_exercise_declares_correct_is_explained_and_leaves_the_score():
    report = mutate_exercise(get("4.3.11"), seeds=1)  # declares P -> N a correct program
    assert [o.status for o in report.outcomes] == [KILLED, EXPLAINED]
    explained = report.outcomes[1]
    assert "one-scan pulse every 1.000 s" in explained.reason
    assert "these differ: Takt1s" in explained.detail  # it does behave differently: explained, not equivalent
    assert report.score == 1.0 and report.misleading == []
    data = json.loads(report.to_json())
    assert data["counts"] == {"killed": 1, "survived": 0, "explained": 1, "equivalent": 0, "stillborn": 0}
    assert data["outcomes"][1]["status"] == "explained" and data["outcomes"][1]["reason"] == explained.reason


def test_one_survivor_among_hundreds_never_shows_as_a_full_score():
    mutant = Mutant(1, "drop", 1, "x", "")
    report = MutationReport("9.9.9", "t", [1], [Outcome(mutant, KILLED, "k")] * 227 + [Outcome(mutant, SURVIVED, "s")])
    console = Console(record=True, width=200)
    print_mutation_report(report, console)
    assert "mutation score: 99.6 %" in console.export_text()


def test_a_declared_mutant_that_does_not_exist_is_an_error_naming_the_exercise():
    stale = dataclasses.replace(get("4.3.11"), spec_equivalent={"P(t.Clock_1Hz, 'AUX') → N(t.Clock_1Hz, 'AU')": "x"})
    with pytest.raises(ExerciseError) as info:
        exercise_mutants(stale)
    message = str(info.value)
    assert message.startswith(f"{stale.defined_at}: exercise 4.3.11: ")  # the file and line that declared it
    assert "which is no mutant of the reference; did you mean \"P(t.Clock_1Hz, 'AUX') → N(t.Clock_1Hz, 'AUX')\"" in (
        message
    )
    with pytest.raises(ExerciseError, match="no mutant of the reference"):
        mutate_exercise(stale, seeds=1)


def test_a_description_that_names_several_mutants_needs_its_line():
    exercise = get("4.3.8")  # ALARM is read on lines 27 and 39 of the reference
    mutants = exercise_mutants(exercise)
    twice = dataclasses.replace(exercise, spec_equivalent={"t.ALARM → not t.ALARM": "x"})
    with pytest.raises(ExerciseError, match=re.escape("lines 27, 39: write 'line N: t.ALARM → not t.ALARM'")):
        declared_equivalents(twice, mutants)
    chosen = dataclasses.replace(exercise, spec_equivalent={"line 39: t.ALARM → not t.ALARM": "x"})
    assert declared_equivalents(chosen, mutants) == {(39, "t.ALARM → not t.ALARM"): "x"}


def test_a_killed_mutant_declared_correct_is_reported_as_misleading():
    exercise = dataclasses.replace(
        get("4.3.11"), spec_equivalent={"P(t.Clock_1Hz, 'AUX') → t.Clock_1Hz": "a level is a pulse too"}
    )
    report = mutate_exercise(exercise, seeds=1)
    assert report.outcomes[0].status == KILLED  # the declaration never turns a kill into an excuse
    assert report.score == 0.5  # and the undeclared P -> N survives
    [line] = report.misleading
    assert line.startswith("line 12: P(t.Clock_1Hz, 'AUX') → t.Clock_1Hz: declared a correct program")
    assert "but killed (seed 1: scenario" in line and "a check is stricter than the spec" in line
    console = Console(record=True, width=200)
    print_mutation_report(report, console)
    assert "misleading declarations" in console.export_text()
    assert json.loads(report.to_json())["misleading"] == [line]


def test_a_declaration_needs_a_reason():
    with pytest.raises(ExerciseError, match=r"spec_equivalent\['OB1: x'\] needs the reason it is correct"):
        dataclasses.replace(get("4.3.11"), spec_equivalent={"OB1: x": " "})


def test_every_shipped_declaration_names_a_mutant_of_its_reference():
    declaring = [e for e in all_exercises() if e.spec_equivalent]
    assert {e.number for e in declaring} >= {"4.3.7", "4.3.8", "4.3.11", "4.3.13", "4.3.14", "4.3.15"}
    for exercise in declaring:
        assert len(declared_equivalents(exercise, exercise_mutants(exercise))) == len(exercise.spec_equivalent)


def test_the_reference_itself_is_equivalent_though_a_scenario_alone_would_not_exercise_a_check():
    # 4.3.5's "placed at S2" alone never runs the belt, so "the belt never runs while S2 sees an object" is not
    # exercised there; the grade of all scenarios exercises it. A mutant stops early only on a real failure.
    exercise = get("4.3.5")
    unchanged = Mutant(1, "none", 1, "unchanged", Path(exercise.reference.path).read_text(encoding="utf-8"))
    report = mutate_exercise(exercise, seeds=2, mutants=[unchanged])
    assert report.outcomes[0].status == EQUIVALENT, report.outcomes[0].detail


def test_a_killed_mutant_stops_at_the_first_scenario_that_kills_it(monkeypatch):
    exercise = get("4.3.5")
    mutant = next(m for m in exercise_mutants(exercise) if m.operator == "negate")
    shortest = min(exercise.scenarios, key=lambda s: s.duration_ns).name
    ran = []
    real_run = engine.run_scenarios

    def counted(exercise, program, *, seed, scenarios, geometry):
        ran.append((str(program), scenarios))
        return real_run(exercise, program, seed=seed, scenarios=scenarios, geometry=geometry)

    monkeypatch.setattr(engine, "run_scenarios", counted)
    report = mutate_exercise(exercise, seeds=1, mutants=[mutant])
    assert report.outcomes[0].status == KILLED
    mutant_runs = [scenarios for program, scenarios in ran if "mutant" in program]
    assert mutant_runs[0] == [shortest] and len(mutant_runs) < len(exercise.scenarios)
    assert report.outcomes[0].detail.startswith("seed 1: scenario ")


def test_the_verdicts_are_those_of_a_whole_grade_and_a_second_run():
    # The oracle is the plain algorithm: grade() each seed, then run every scenario again for the behaviour.
    exercise = get("4.3.12")
    mutants = exercise_mutants(exercise)[::3]
    report = mutate_exercise(exercise, seeds=1, mutants=mutants)
    reference = exercise.reference.program()
    failed = {f"{c.scenario}: {c.check}" for c in grade(exercise, reference, seed=1).failed()}

    def ran(program):
        runs = []
        for scenario in exercise.scenarios:
            sim = exercise.simulation(program, scenario, seed=1)
            sim.run()
            runs.append(behaviour(exercise, sim.trace, "", edge_memories(reference), getattr(program, "filename", "")))
        return runs

    theirs = ran(reference)
    expected = []
    for m in mutants:
        program = Program(m.source, f"<mutant {m.number}>")
        if {f"{c.scenario}: {c.check}" for c in grade(exercise, program, seed=1).failed()} - failed:
            expected.append(KILLED)
        else:
            expected.append(EQUIVALENT if ran(program) == theirs else SURVIVED)
    assert [SURVIVED if o.status == EXPLAINED else o.status for o in report.outcomes] == expected
    assert KILLED in expected and len(set(expected)) > 1


def test_a_mutant_that_does_not_load_is_counted_apart():
    broken = Mutant(1, "drop", 2, "statement dropped", "def OB1(t):\n    t.LED = q\n")
    report = mutate_exercise(get("4.3.1"), seeds=1, mutants=[broken])
    assert report.outcomes[0].status == STILLBORN
    assert "unknown name 'q'" in report.outcomes[0].detail
    assert report.score is None and report.count(KILLED) == 0


def test_parallel_grading_gives_the_same_outcomes():
    exercise = get("4.3.20")
    one = mutate_exercise(exercise, seeds=1, jobs=1)
    two = mutate_exercise(exercise, seeds=1, jobs=2)
    assert [(o.mutant, o.status, o.detail) for o in one.outcomes] == [
        (o.mutant, o.status, o.detail) for o in two.outcomes
    ]
    assert len(one.outcomes) == 7


def test_the_cli_prints_the_score_and_writes_json(tmp_path, capsys):
    out = tmp_path / "mutants.json"
    assert main(["mutate", "4.3.1", "--seeds", "1", "--json", str(out)]) == 0
    text = capsys.readouterr().out
    assert "mutation score: 100 %" in text and "1 killed, 0 survived" in text
    data = json.loads(out.read_text(encoding="utf-8"))
    assert data["score"] == 1.0 and data["counts"]["killed"] == 1
    assert data["outcomes"][0]["mutant"]["label"] == "line 5: t.TLACIDLO → not t.TLACIDLO"


def test_the_cli_lists_explained_mutants_with_their_reason(capsys, monkeypatch):
    monkeypatch.setenv("COLUMNS", "300")  # the reason on one line
    assert main(["mutate", "4.3.11", "--seeds", "1"]) == 0
    text = capsys.readouterr().out
    assert "explained mutants (correct programs by the spec's words, not counted)" in text
    assert "N(t.Clock_1Hz, 'AUX')" in text and "one-scan pulse every 1.000 s" in text
    assert "mutation score: 100 %" in text and "1 killed, 0 survived, 1 explained" in text


def test_the_cli_refuses_zero_seeds(capsys):
    assert main(["mutate", "4.3.1", "--seeds", "0"]) == 2
    assert "--seeds and --jobs must be at least 1" in capsys.readouterr().err


def test_a_cyclic_interrupt_run_in_ob1_instead():
    source = "def blink(t):\n    t.D1 = not t.D1\n\n\nOB30 = CyclicInterrupt(blink, period='1s')\n"
    mutants = {m.operator: m for m in derive_mutants(source, small_table())}
    assert str(mutants["task"]) == "line 5: OB30: its networks run in OB1, every scan, instead of every '1s'"
    assert mutants["task"].source.rstrip().endswith("OB1 = blink")
    assert set(Program(mutants["task"].source).tasks) == {"OB1"}
