"""The independent corpus (tests/corpus/): programs written apart from the shipped solutions, the way
students write them, graded on the seeds 1..20. A correct one passes every check on every seed; a
buggy one fails, on every seed, the checks that tests/corpus/manifest.toml names for it.
"""

from __future__ import annotations

import tomllib
from pathlib import Path

import pytest
from seeded import SEEDS, assert_fails, assert_passes

from exercises import get

CORPUS = Path(__file__).parents[1] / "corpus"
MANIFEST = tomllib.loads((CORPUS / "manifest.toml").read_text(encoding="utf-8"))


def folder(number: str) -> Path:
    """``4.3.3`` -> tests/corpus/4_3_03."""
    major, minor, item = number.split(".")
    return CORPUS / f"{major}_{minor}_{int(item):02d}"


CASES = [
    pytest.param(number, name, tuple(fails), seed, id=f"{number}-{name.removesuffix('.py')}-{seed}")
    for number, programs in MANIFEST.items()
    for name, fails in programs.items()
    for seed in SEEDS
]


@pytest.mark.parametrize(("number", "name", "fails", "seed"), CASES)
def test_corpus_program_grades_as_the_manifest_says(number, name, fails, seed):
    exercise, path = get(number), folder(number) / name
    if fails:
        assert_fails(exercise, path, seed, fails)
    else:
        assert_passes(exercise, path, seed)


def test_every_corpus_program_is_in_the_manifest():
    on_disk = {(p.parent.name, p.name) for p in CORPUS.glob("*/*.py")}
    listed = {(folder(number).name, name) for number, programs in MANIFEST.items() for name in programs}
    assert on_disk == listed
