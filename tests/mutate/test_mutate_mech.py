"""Mutants of PLC836 mechanism programs (``.mech``): the operators, and the exercises P-01/P-02 whose
checks kill them (``plcsim mutate`` picks the operators by the reference's suffix)."""

from __future__ import annotations

from exercises import get
from plcsim.mutate.engine import EXPLAINED, KILLED, exercise_mutants, mutate_exercise
from plcsim.mutate.mech import derive_mech_mutants

PROGRAM = """EQUI D1,50 ;1 s
MECH_BEGIN M
FL 0,SMP
LDR KSMP
LA -X
TEX1 CITAC,D1,ERR,04
TIM -,10
EX
ERR: STO BZH11
MECH_END M
"""


def labels(text: str = PROGRAM) -> list[str]:
    return [str(m) for m in derive_mech_mutants(text)]


def test_the_chapter_s_slips_are_among_the_operators():
    found = labels()
    for label in (
        "line 1: EQUI D1,50 → EQUI D1,49",  # a constant a preset step off
        "line 3: FL 0,SMP → FL 1,SMP",  # set for reset
        "line 4: LDR KSMP → LDR -KSMP",  # a negated contact
        "line 5: LA -X → LO -X",  # series for parallel
        "line 5: LA -X → LA X",
        "line 6: TEX1 CITAC,D1,ERR,04 → TEX0 CITAC,D1,ERR,04",  # the polarity pitfall
        "line 6: TEX1 CITAC,D1,ERR,04 → EX1",  # the time limit left out
        "line 6: TEX1 CITAC,D1,ERR,04 → TEX1 CITAC,D1,ERR,03",  # another error number
        "line 7: TIM -,10 → TIM -,9",
        "line 8: EX → BEX",  # a state that costs no scan
        "line 8: EX dropped",  # the missing EX
    ):
        assert label in found, label


def test_structure_is_left_alone_and_a_dropped_line_keeps_its_label():
    mutants = derive_mech_mutants(PROGRAM)
    assert not any("MECH_BEGIN" in m.description or "MECH_END" in m.description for m in mutants)
    dropped = next(m for m in mutants if m.description == "STO BZH11 dropped")
    assert dropped.source.splitlines()[8] == "ERR:"
    assert "line 8: EX ⇄ STO BZH11 (lines 8 and 9)" not in labels()  # no swap across a label


def test_p01_mutants_are_killed_by_the_check_that_explains_them():
    exercise = get("P-01")
    chosen = [
        m
        for m in exercise_mutants(exercise)
        if m.description in ("TEX0 CITAC,D1,CW_ERR,05 → TEX1 CITAC,D1,CW_ERR,05", "TIM CITAC,D02 dropped")
    ]
    report = mutate_exercise(exercise, seeds=1, mutants=chosen)
    assert report.reference_failures == []
    assert [o.status for o in report.outcomes] == [KILLED, KILLED]
    assert "SMN is switched on 0.2 s after KSMP opens" in report.outcomes[0].detail
    assert "an SMN that never closes" in report.outcomes[1].detail


def test_p02_s_bex_for_ex_is_explained_by_the_chapter():
    exercise = get("P-02")
    bex = [m for m in exercise_mutants(exercise) if m.description == "EX → BEX"]
    report = mutate_exercise(exercise, seeds=1, mutants=bex)
    assert [o.status for o in report.outcomes] == [EXPLAINED]
