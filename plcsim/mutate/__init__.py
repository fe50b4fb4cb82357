"""Mutation testing of an exercise's checks: mutants of the reference, graded like submissions."""

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

__all__ = [
    "Mutant",
    "Outcome",
    "MutationReport",
    "derive_mutants",
    "exercise_mutants",
    "declared_equivalents",
    "mutate_exercise",
    "behaviour",
    "edge_memories",
    "print_mutation_report",
    "KILLED",
    "SURVIVED",
    "EXPLAINED",
    "EQUIVALENT",
    "STILLBORN",
]
