"""The chapter's mechanism examples M-01..M-08 (``examples/mechanisms/``) and their I/O tables.

Each example is a ``.mech`` file (the chapter's text) and, where the chapter's example is a program,
the same program in the Python form; both run on the S7 runtime against the same I/O table.
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

from plcsim import CPU, Tag
from plcsim.frontends import read_program
from plcsim.tags.types import Int

FOLDER = Path(__file__).resolve().parent.parent / "examples" / "mechanisms"

SPINDLE_TAGS = {
    "START": Tag("%I0.0"),
    "KSMP": Tag("%I0.1"),
    "KSMN": Tag("%I0.2"),
    "SMP": Tag("%Q0.0"),
    "SMN": Tag("%Q0.1"),
    "BZH11": Tag("%MW10", Int),
}
TAGS: dict[str, dict[str, Tag]] = {
    "m01_latch": {
        "NASTAV1": Tag("%I0.0"),
        "NASTAV2": Tag("%I0.1"),
        "NULUJ": Tag("%I0.2"),
        "BUNKA": Tag("%Q0.0"),
    },
    "m02_nazev": {
        "START": Tag("%I0.0"),
        "KONTAKT1": Tag("%I0.1"),
        "KONTAKT2": Tag("%I0.2"),
        "KONTAKT3": Tag("%I0.3"),
        "HYDRAULIKA": Tag("%Q0.0"),
        "POHON": Tag("%Q0.1"),
    },
    "m03_window": {"VST1": Tag("%I0.0"), "VST2": Tag("%I0.1"), "VYST1": Tag("%Q0.0")},
    "m04_prep_cw": SPINDLE_TAGS,
    "m05_prep_cw_timeout": SPINDLE_TAGS,
    "m06_cwccw": SPINDLE_TAGS,
    "m07_cwccw_tex": SPINDLE_TAGS,
    "m08_typed": {"START": Tag("%I0.0"), "VST1": Tag("%I0.1"), "VST2": Tag("%I0.2")},
}
BOTH_FORMS = sorted(p.stem for p in FOLDER.glob("*.py"))
"""The examples written in both forms (M-08 is syntax: a ``.mech`` file only)."""


def path(example: str, suffix: str) -> Path:
    return FOLDER / f"{example}{suffix}"


def cpu(example: str, suffix: str = ".mech", **options: Any) -> CPU:
    """A CPU running the example in the form ``suffix`` (``.mech`` or ``.py``), in RUN."""
    return CPU(tags=TAGS[example], program=read_program(path(example, suffix)), **options)
