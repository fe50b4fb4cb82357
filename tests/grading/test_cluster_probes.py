"""The batch's trusted probe (plcsim.grading.sandbox.probes.Probes): run once per (exercise, scenario, seed) for a
whole batch instead of once per submission, and out of reach of the submissions: every submission is
validated against its own copy, and hostile children graded in the same batch leave the cached
probes as a fresh probe computes them.
"""

from __future__ import annotations

import json
import shutil

import pytest

from exercises import get
from plcsim.grading.batch import grade_batch
from plcsim.grading.sandbox import probes as sandbox_probes
from plcsim.grading.sandbox import readable as sandbox_readable
from plcsim.grading.sandbox.probes import Probes

# one xdist worker runs them: they share one local Dask cluster (a second would double the workers)
pytestmark = pytest.mark.xdist_group("cluster")


@pytest.fixture(scope="module")
def ex4():
    return get("4.3.4")  # two scenarios


def test_each_submission_gets_its_own_copy_of_a_probe(ex4):
    probes = Probes.of(ex4, ex4.scenarios, seed=1)
    first = probes.expected(ex4, ex4.scenarios[0], 1)
    first.kinds.clear()
    first.meta["cycle_ns"] = 1
    again = probes.expected(ex4, ex4.scenarios[0], 1)
    assert again == Probes.of(ex4, ex4.scenarios, seed=1).by_scenario["on and off"]
    assert again.kinds and again.meta["cycle_ns"] != 1


def test_a_seed_or_scenario_the_batch_did_not_probe_is_probed_afresh(ex4, monkeypatch):
    probes = Probes.of(ex4, ex4.scenarios[:1], seed=1)
    calls = []
    monkeypatch.setattr(sandbox_probes, "_expected", lambda ex, s, seed: calls.append((s.name, seed)) or "fresh")
    assert probes.expected(ex4, ex4.scenarios[0], 2) == "fresh"
    assert probes.expected(ex4, ex4.scenarios[1], 1) == "fresh"
    assert probes.expected(ex4, ex4.scenarios[0], 1) != "fresh"
    assert calls == [("on and off", 2), ("both pressed", 1)]


def test_a_batch_probes_each_scenario_once(ex4, tmp_path, monkeypatch):
    for sol in ex4.solutions:
        shutil.copy(sol.path, tmp_path / f"{sol.name}.py")
    calls = []
    real = sandbox_probes._expected
    monkeypatch.setattr(sandbox_probes, "_expected", lambda ex, s, seed: calls.append(s.name) or real(ex, s, seed))
    reports = grade_batch(ex4, sorted(tmp_path.glob("*.py")), jobs=2, seed=3)
    assert [(r.student, r.score, r.max_score) for r in reports] == [
        ("reference", 10.0, 10.0),
        ("wrong-set-reset", 8.0, 10.0),
        ("wrong-start-dominant", 7.0, 10.0),
    ]
    assert calls == ["on and off", "both pressed"]  # not 3 × 2


def test_hostile_children_in_a_batch_leave_the_cached_probes_untouched(tmp_path, monkeypatch):
    ex1 = get("4.3.1")
    tampers = ["rename-signal", "other-seed", "beyond-horizon", "bool-two", "late-row"]
    orders = [{"do": "tamper", "how": how} for how in tampers] + [{"do": "reference"}]
    for k, order in enumerate(orders):
        (tmp_path / f"{k}_{order.get('how', order['do'])}.py").write_text(json.dumps(order), encoding="utf-8")
    made, probe = [], Probes.of

    def kept(cls, *args):
        made.append(probe(*args))
        return made[-1]

    monkeypatch.setattr(Probes, "of", classmethod(kept))
    reports = grade_batch(ex1, sorted(tmp_path.glob("*.py")), jobs=2, child_entry="sandbox_hostile_child")
    assert [r.error_kind for r in reports] == ["invalid result"] * 5 + [None]
    assert (reports[-1].passed, reports[-1].score) == (True, 3.0)  # against the same probes
    (probes,) = made
    monkeypatch.undo()
    assert probes.by_scenario == Probes.of(ex1, ex1.scenarios, seed=1).by_scenario


def test_what_a_child_may_read_is_walked_once_per_batch(ex4, tmp_path):
    paths = [tmp_path / f"student{k}.py" for k in range(3)]
    sandbox_readable._granted.cache_clear()
    lists = [sandbox_readable.readable_paths(ex4, p) for p in paths]
    info = sandbox_readable._granted.cache_info()
    assert (info.misses, info.hits) == (1, 2)
    sandbox_readable._granted.cache_clear()
    assert lists[0] == lists[1] == lists[2] == sandbox_readable.readable_paths(ex4, paths[0])  # a fresh walk: the same
    assert not any(str(tmp_path) in entry for entry in lists[0])
    assert not any("solutions" in entry for entry in lists[0])
