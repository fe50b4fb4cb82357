"""The module paths of plcsim 0.1 keep importing for one release (plcsim.core.moved): every public name
each old module defined (tests/core/names_of_0_1.json, read from the 0.1 sources) is found under its
old path, an alias says where the module went, and the public packages import without a warning."""

from __future__ import annotations

import importlib
import json
import subprocess
import sys
import warnings
from pathlib import Path

import pytest

from plcsim.core.moved import MODULES, PACKAGES, new_home

NAMES = json.loads((Path(__file__).parent / "names_of_0_1.json").read_text(encoding="utf-8"))
PUBLIC = ["plcsim.check", "plcsim.scenario", "plcsim.exercise", "plcsim.plant", "plcsim.trace", "plcsim.grading"]
PUBLIC += ["plcsim.sim", "plcsim.tags", "plcsim.mutate", "plcsim.frontends", "plcsim.frontends.il"]
PUBLIC += [f"plcsim.check.{m}" for m in ("base", "conditions", "occurrences", "quantities", "static", "temporal")]


def old_import(name: str) -> tuple[object, list[warnings.WarningMessage]]:
    """Import ``name`` as a fresh process would see it the first time, with the warnings it gave."""
    for key in [k for k in sys.modules if k == name or k.startswith(name + ".")]:
        if new_home(key) is not None:
            del sys.modules[key]
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        module = importlib.import_module(name)
    return module, [w for w in caught if issubclass(w.category, DeprecationWarning)]


def test_every_module_of_0_1_is_either_still_there_or_moved():
    assert set(NAMES) == {name for name in NAMES if name in PUBLIC or new_home(name) is not None}


@pytest.mark.parametrize("old", sorted(name for name in NAMES if name not in PUBLIC))
def test_an_old_path_imports_warns_where_it_went_and_has_every_name(old: str):
    module, caught = old_import(old)
    assert caught, f"importing {old} gave no DeprecationWarning"
    assert any(home in str(w.message) for w in caught for home in new_home(old))
    missing = [name for name in NAMES[old] if not hasattr(module, name)]
    assert missing == [], f"{old} lacks {missing}"


@pytest.mark.parametrize("public", sorted(name for name in NAMES if name in PUBLIC))
def test_a_public_path_imports_without_a_warning_and_has_every_name(public: str):
    module, caught = old_import(public)
    assert caught == []
    missing = [name for name in NAMES[public] if not hasattr(module, name)]
    assert missing == [], f"{public} lacks {missing}"


def test_a_moved_module_is_the_module_itself_so_a_monkeypatch_reaches_it():
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", DeprecationWarning)
        import plcsim.cpu
        import plcsim.tecomat.cpu
    from plcsim.controllers.s7 import cpu
    from plcsim.controllers.tecomat import cpu as tecomat_cpu

    assert plcsim.cpu is cpu and plcsim.tecomat.cpu is tecomat_cpu


def test_the_tables_name_modules_that_exist():
    homes = {home for tuple_ in MODULES.values() for home in tuple_} | set(PACKAGES.values())
    for home in sorted(homes):
        importlib.import_module(home)


def test_an_old_import_works_in_a_fresh_interpreter():
    code = (
        "import warnings; warnings.simplefilter('error')\n"
        "try:\n    from plcsim.cpu import CPU\nexcept DeprecationWarning as w:\n    print(w)\n"
        "warnings.simplefilter('ignore')\n"
        "from plcsim.cpu import CPU; from plcsim.live import open_live; from plcsim.profiles.s7 import PROFILE\n"
        "import plcsim; print(CPU is plcsim.CPU, PROFILE.name)\n"
    )
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert done.stdout.splitlines() == [
        "plcsim.cpu moved to plcsim.controllers.s7.cpu; import it from there (the old path is kept for one release)",
        "True s7-1200",
    ]
