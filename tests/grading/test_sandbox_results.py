"""The grader's side of the result pipe (plcsim.grading.run_result): a message built from a real run of the
reference of 4.3.1 decodes to the same trace and grades 3/3 here; each forgery of it is refused
with a reason, before any check reads it. No child process is started: these are the decoder alone.
"""

from __future__ import annotations

import numpy as np
import pytest
from sandbox_hostile_child import _TAMPER, _retitle

from exercises import get
from plcsim.grading.report import Report
from plcsim.grading.run import run_scenarios
from plcsim.grading.run_result import InvalidResultError, decode, encode_failure, encode_runs, message_length
from plcsim.grading.sandbox.probes import _expected
from plcsim.grading.scoring import evaluate

# one xdist worker runs them in turn: they look for the hostile child's leftovers machine-wide and
# time their limits, so two at once on two cores would see each other
pytestmark = pytest.mark.xdist_group("sandbox")


@pytest.fixture(scope="module")
def ex1():
    return get("4.3.1")


@pytest.fixture(scope="module")
def honest(ex1):
    runs, _ = run_scenarios(ex1, ex1.reference.program(), seed=1)
    return runs, encode_runs(runs)


@pytest.fixture(scope="module")
def expected(ex1):
    return [_expected(ex1, s, 1) for s in ex1.scenarios]


def grade_message(ex1, message, expected):
    runs = decode(message, expected, 1)
    return evaluate(ex1, runs, None, Report(ex1.number, ex1.title, "x.py"))


def test_an_honest_message_decodes_to_the_same_trace_and_grades_full_marks(ex1, honest, expected):
    runs, message = honest
    assert message_length(message) == len(message)
    (back,) = decode(message, expected, 1)
    (run,) = runs
    assert back.trace.names == list(expected[0].kinds) == ["TLACIDLO", "LED"]
    assert np.array_equal(back.trace.table, run.trace.table)
    assert back.trace.events == run.trace.events
    assert (back.simulated_ns, back.scans, back.cpu_mode) == (4_000_000_000, 4000, "RUN")
    assert back.trace.meta["cycle_ns"] == 1_000_000 and back.trace.meta["end_ns"] == 4_000_000_000
    r = grade_message(ex1, message, expected)
    assert (r.passed, r.score, r.max_score) == (True, 3.0, 3.0)


@pytest.mark.parametrize(
    ("how", "why"),
    [
        ("rename-signal", "the trace lacks the exercise's signals ['TLACIDLO']"),
        ("drop-scenario", "has the scenarios []; expected ['presses']"),
        ("other-seed", "the child ran seed 99, not 1"),
        ("beyond-horizon", "simulated time 1000000000000000000 is outside 0..4000000000 ns"),
        ("bool-two", "the Bool signal 'TLACIDLO' holds values other than 0 and 1"),
        ("late-row", "a trace row lies outside 0..4000000000 ns"),
        ("trailing-bytes", "bytes; its header announces"),
        ("truncated", "bytes; its header announces"),
    ],
)
def test_each_forgery_of_the_honest_message_is_refused(ex1, honest, expected, how, why):
    forged = _TAMPER[how](honest[1])
    if how == "drop-scenario":  # drop its table too, so that only the scenario list is wrong
        forged = forged[: len(forged) - len(honest[0][0].trace.table.tobytes())]
    with pytest.raises(InvalidResultError) as caught:
        grade_message(ex1, forged, expected)
    assert why in str(caught.value)


def change_first(key, value):
    def change(header):
        header["runs"][0][key] = value

    return change


@pytest.mark.parametrize(
    ("change", "why"),
    [
        (change_first("cpu_mode", "PASSED"), "CPU mode 'PASSED' is neither RUN nor STOP"),
        (change_first("scans", -1), "scan count -1 is impossible"),
        (change_first("scans", True), "scan count True is impossible"),
        (change_first("kinds", {"TLACIDLO": "output", "LED": "output"}), "['TLACIDLO'] have the wrong kind or type"),
        (change_first("types", {"TLACIDLO": "real", "LED": "bool"}), "['TLACIDLO'] have the wrong kind or type"),
        (change_first("events", [{"t_ns": 1, "source": "grader", "kind": "PASS"}]), "fields of a trace event"),
        (change_first("cpu_error", "x" * 30_000), "CPU error is not a string of at most 20000 characters"),
        (change_first("warnings", "all checks passed"), "warnings are not a bounded list"),
        (lambda h: h.update(kind="report", score=3), "not a runs or failure message"),
        (lambda h: h.update(score=3), "fields ['kind', 'runs', 'score']"),
    ],
    ids=["mode", "scans", "bool-scans", "kind", "type", "event", "long-text", "warnings", "report", "score"],
)
def test_forged_header_fields_are_refused(ex1, honest, expected, change, why):
    with pytest.raises(InvalidResultError) as caught:
        grade_message(ex1, _retitle(honest[1], change), expected)
    assert why in str(caught.value)


def test_an_extra_column_is_kept_out_of_what_the_checks_read(ex1, honest, expected):
    """A child may trace the program's own tags; they never reach the checks (which see the exercise's)."""
    runs, _ = honest
    table = runs[0].trace.table
    wider = np.hstack([table, table[:, -1:]])
    message = _retitle(
        encode_runs(runs),
        lambda h: h["runs"][0].update(
            names=["TLACIDLO", "LED", "MINE"],
            kinds={"TLACIDLO": "input", "LED": "output", "MINE": "memory"},
            types={"TLACIDLO": "bool", "LED": "bool", "MINE": "bool"},
        ),
    )
    start = len(message) - len(table.tobytes())
    message = message[:start] + wider.astype("<f8").tobytes()
    (back,) = decode(message, expected, 1)
    assert back.trace.names == ["TLACIDLO", "LED"] and back.trace.table.shape == (4000, 5)


def test_a_failure_message_can_only_lose_points(ex1, expected):
    assert decode(encode_failure("program error", "line 3: bad"), expected, 1) == ("program error", "line 3: bad")
    with pytest.raises(InvalidResultError, match="unknown failure kind 'passed'"):
        decode(encode_failure("passed", "all good"), expected, 1)


def test_a_message_announcing_more_than_it_may_is_refused_at_its_header():
    from plcsim.grading.run_result import LENGTH, MAGIC

    with pytest.raises(InvalidResultError, match="header has 1099511627776 bytes"):
        message_length(MAGIC + LENGTH.pack(1 << 40))
    with pytest.raises(InvalidResultError, match="does not start with the result marker"):
        message_length(b"PASSED 3/3")
    assert message_length(MAGIC[:5]) is None  # a prefix: wait for more
