"""The checker language (plcsim.check) on small hand-built traces: every construct passes and fails
exactly where it should, and a failure says what was expected, what happened and when.

The traces have one row per 1 ms scan: row k starts at k ms (inputs as read) and ends at k+1 ms
(outputs as written). Signals named D... are outputs, the others inputs.
"""

from __future__ import annotations

import pytest

from plcsim import CPU, Tag
from plcsim.check import (
    Span,
    action,
    all_of,
    always,
    any_of,
    becomes,
    count,
    durations,
    duty,
    evaluate_all,
    event,
    eventually,
    falls,
    final,
    holds,
    implies,
    measure,
    never,
    not_,
    off,
    program_uses_no,
    rises,
    same,
    spacing,
    value,
    value_at,
)
from plcsim.core.errors import ConfigurationError
from plcsim.trace.facade import Trace, TraceEvent

MS = 1_000_000


def make_trace(cols: dict[str, list], events=(), types: dict[str, str] | None = None) -> Trace:
    names = list(cols)
    kinds = {n: ("output" if n.startswith("D") else "input") for n in names}
    types = {n: "bool" for n in names} | (types or {})
    tr = Trace(names, kinds, types)
    rows = len(cols[names[0]])
    for k in range(rows):
        values = tuple(bool(cols[n][k]) if types[n] == "bool" else cols[n][k] for n in names)
        tr.add_row(k * MS, (k + 1) * MS, 1, values)
    tr.meta.update(cycle_ns=MS, end_ns=rows * MS)
    for e in events:
        tr.add_event(e)
    return tr


def verdict(check, tr, analysis=None):
    ((_, v),) = evaluate_all([check], tr, analysis)
    return v


#                   row: 0  1  2  3  4  5  6  7  8  9
CONVEYOR = {
    "S1": [0, 0, 1, 1, 0, 0, 0, 1, 0, 0],
    "S2": [0, 0, 0, 0, 0, 1, 1, 0, 0, 0],
    "D1": [0, 0, 1, 1, 1, 0, 0, 1, 1, 1],  # set in the scan that sees S1, reset in the scan that sees S2
}
LATE = {**CONVEYOR, "D1": [0, 0, 0, 1, 1, 0, 0, 1, 1, 1]}  # the first start comes one scan late


@pytest.fixture
def conveyor():
    return make_trace(CONVEYOR)


@pytest.fixture
def late():
    return make_trace(LATE)


# -- occurrences on the trace ------------------------------------------------------------------------


def test_edges_of_inputs_and_outputs(conveyor):
    assert conveyor.rises("S1").tolist() == [2 * MS, 7 * MS]  # an input: when the scan read it
    assert conveyor.rises("D1").tolist() == [3 * MS, 8 * MS]  # an output: when the scan wrote it
    assert conveyor.falls("D1").tolist() == [6 * MS]
    assert conveyor.intervals("D1") == [(3 * MS, 6 * MS), (8 * MS, None)]


# -- response: within / between / after --------------------------------------------------------------


def test_within_passes_when_every_trigger_is_answered(conveyor):
    check = rises("D1").within("1 scan").after(rises("S1"))
    assert check.describe() == "D1 rises within 1 scan after S1 rises"
    v = verdict(check, conveyor)
    assert (v.passed, v.message, v.signals) == (True, "2 time(s), each answered within 1 scan", ["S1", "D1"])


def test_within_fails_with_expected_happened_and_when(late):
    v = verdict(rises("D1").within("1 scan").after(rises("S1")), late)
    assert not v.passed
    assert v.message == (
        "after S1 rises at 2 ms, expected D1 rises within 1 scan (between 2 ms and 3 ms); "
        "it happened 2 ms after it, at 4 ms"
    )
    assert (v.at_ns, v.window) == (2 * MS, (2 * MS, 3 * MS))


def test_within_fails_when_the_answer_never_comes():
    tr = make_trace({"S1": [0, 1, 0, 0], "D1": [0, 0, 0, 0]})
    v = verdict(rises("D1").within("2 scans").after(rises("S1")), tr)
    assert v.message == (
        "after S1 rises at 1 ms, expected D1 rises within 2 scans (between 1 ms and 3 ms); it did not happen afterwards"
    )


def test_between(late, conveyor):
    check = rises("D1").between("2 scans", "3 scans").after(rises("S1"))
    assert check.describe() == "D1 rises between 2 scans and 3 scans after S1 rises"
    v = verdict(check, conveyor)
    assert not v.passed
    assert v.message == (
        "after S1 rises at 2 ms, expected D1 rises between 2 scans and 3 scans (between 4 ms and 5 ms); "
        "it happened 1 ms after it, at 3 ms"
    )
    v = verdict(rises("D1").between("1 scan", "2 scans").after(rises("S1")), late)
    assert (v.passed, v.message) == (True, "2 time(s), each answered between 1 scan and 2 scans")


def test_provided_filters_the_triggers():
    #        row: 0  1  2  3  4  5
    tr = make_trace({"S1": [0, 1, 0, 1, 0, 0], "S2": [0, 1, 1, 0, 0, 0], "D1": [0, 0, 0, 1, 1, 1]})
    plain = rises("D1").within("1 scan").after(rises("S1"))
    assert not verdict(plain, tr).passed  # the press at 1 ms (with S2) was not answered
    provided = rises("D1").within("1 scan").after(rises("S1"), provided=off("S2"))
    assert provided.describe() == "D1 rises within 1 scan after S1 rises while not S2"
    v = verdict(provided, tr)
    assert (v.passed, v.message) == (True, "1 time(s), each answered within 1 scan")


def test_at_least_demands_enough_triggers(conveyor):
    v = verdict(rises("D1").within("1 scan").after(rises("S1"), at_least=3), conveyor)
    assert not v.passed
    assert v.message == (
        "expected S1 rises at least 3 time(s) to check that D1 rises within 1 scan after S1 rises; "
        "it happened 2 time(s)"
    )
    v = verdict(falls("D1").within("1 scan").after(rises("S2")), make_trace({"S2": [0, 0], "D1": [0, 0]}))
    assert v.message.endswith("it happened 0 time(s)") and not v.passed


def test_scenario_actions_as_triggers():
    tr = make_trace({"D1": [0, 1, 1, 0]}, events=[TraceEvent(1 * MS, "scenario", "press", "TL")])
    check = rises("D1").within("1 scan").after(action("press", "TL"))
    assert check.describe() == "D1 rises within 1 scan after the operator's press TL"
    assert verdict(check, tr).passed
    assert not verdict(rises("D1").within("1 scan").after(action("press", "ACK")), tr).passed


# -- never / always ----------------------------------------------------------------------------------


def test_never_a_condition(conveyor):
    assert verdict(never(all_of("D1", "S2")), conveyor).passed
    v = verdict(never(all_of("D1", "S1")), conveyor)
    assert not v.passed
    assert v.message == "expected never D1 and S1; it held in the scan at 2 ms (D1=TRUE, S1=TRUE)"
    assert (v.at_ns, v.window, v.signals) == (2 * MS, (2 * MS, 3 * MS), ["D1", "S1"])


def test_never_for_more_than(conveyor):
    # D1 is on for 3 scans (2..5 ms) and for the last 3 scans
    check = never("D1").for_more_than("3 scans")
    assert check.describe() == "never D1 for more than 3 scans"
    assert verdict(check, conveyor).passed
    v = verdict(never("D1").for_more_than("2 scans"), conveyor)
    assert (v.passed, v.message) == (False, "expected never D1; it held in the scan at 2 ms (D1=TRUE)")
    assert not verdict(never("D1").for_more_than("3ms - 1 scan"), conveyor).passed


def test_never_during_a_window(conveyor):
    assert verdict(never("D1").during("5ms", "7ms"), conveyor).passed  # rows 5 and 6
    v = verdict(never("D1").during("5ms", "8ms"), conveyor)
    assert (v.passed, v.at_ns) == (False, 7 * MS)


def test_never_an_event():
    fell = TraceEvent(2 * MS, "plant", "part fell off", "D1", "p1")
    tr = make_trace({"D1": [0, 1, 1, 0]}, events=[fell, TraceEvent(3 * MS, "plant", "part fell off", "D1", "p2")])
    v = verdict(never(event("part fell off")), tr)
    assert v.message == "expected never 'part fell off'; it happened 2 time(s), first at 2 ms (D1, p1)"
    assert (v.passed, v.at_ns) == (False, 2 * MS)
    assert verdict(never(event("part fell off")).during("0ms", "2ms"), tr).passed
    assert verdict(never(event("part jammed")), tr).message == "it never happened"
    # the subject filters: a part name or the sensor
    assert verdict(never(event("part fell off", "p3")), tr).passed
    assert not verdict(never(event("part fell off", "p2")), tr).passed


def test_always(conveyor):
    check = always(implies("S2", off("D1")))
    assert check.describe() == "always not S2 or not D1"
    assert verdict(check, conveyor).passed
    v = verdict(always(implies("S1", "D1")), late := make_trace(LATE))
    assert (v.passed, v.message) == (
        False,
        "expected always not S1 or D1; it failed in the scan at 2 ms (S1=TRUE, D1=FALSE)",
    )
    assert v.window == (2 * MS, 3 * MS)
    assert verdict(always(implies("S1", "D1")).during("3ms", "10ms"), late).passed
    assert verdict(always(implies("S1", "D1")).except_for("1 scan"), late).passed
    assert not verdict(always("D1").except_for("1 scan"), late).passed
    assert verdict(always("D1").except_for("3 scans"), late).passed


# -- holds ---------------------------------------------------------------------------------------------


def test_holds_until(conveyor):
    check = holds("D1").until(rises("S2"))
    assert check.describe() == "D1 holds until S2 rises"
    assert verdict(check, conveyor).message == "it held as required (2 time(s))"
    broken = make_trace({**CONVEYOR, "D1": [0, 0, 1, 1, 0, 0, 0, 1, 1, 1]})  # D1 drops at 4 ms, before S2
    v = verdict(check, broken)
    assert not v.passed
    assert v.message == "expected D1 to hold until S2 rises; it became true at 2 ms and stopped at 4 ms without it"
    assert (v.at_ns, v.window) == (4 * MS, (2 * MS, 4 * MS))
    v = verdict(holds("D1").until(rises("S2")), make_trace({"S2": [0, 0], "D1": [0, 0]}))
    assert v.message == "expected D1 to hold at some point; it never did"


def test_holds_to_the_end():
    check = holds("LED").to_the_end()
    assert check.describe() == "LED holds to the end of the run"
    assert verdict(check, make_trace({"LED": [0, 0, 1, 1, 1]})).passed
    v = verdict(check, make_trace({"LED": [0, 1, 1, 0, 1]}))  # a coil: it goes out at 3 ms, then lights again
    assert v.message == "expected LED to hold to the end of the run; it became true at 1 ms and stopped at 3 ms"
    assert (v.passed, v.at_ns, v.window) == (False, 3 * MS, (1 * MS, 3 * MS))
    assert not verdict(check, make_trace({"LED": [0, 0, 0]})).passed


def test_holds_for_at_least(conveyor):
    assert verdict(holds("D1").for_at_least("3 scans"), conveyor).passed
    v = verdict(holds("D1").for_at_least("4 scans"), conveyor)
    assert v.message == "expected D1 to hold at least 4 scans; from 2 ms it held only 3 ms"
    assert (v.passed, v.at_ns, v.window) == (False, 2 * MS, (2 * MS, 5 * MS))


# -- eventually ------------------------------------------------------------------------------------------


def test_eventually_before(conveyor):
    v = verdict(eventually("S2").before("6ms"), conveyor)
    assert (v.passed, v.message, v.at_ns) == (True, "first at 5 ms", 5 * MS)
    v = verdict(eventually("S2").before("5ms"), conveyor)
    assert (v.passed, v.message) == (False, "expected S2 before 5 ms; it first happened at 5 ms")
    assert verdict(eventually(rises("D1")).before("3ms + 1 scan"), conveyor).passed
    v = verdict(eventually(event("part entered", "S2")), conveyor)
    assert not v.passed and v.message.endswith("; it never happened")


# -- quantities -------------------------------------------------------------------------------------------


def test_count(conveyor):
    assert verdict(count(rises("D1")).equals(2), conveyor).message == "measured 2"
    v = verdict(count(rises("D1")).equals(3), conveyor)
    assert (v.passed, v.message) == (False, "expected number of times D1 rises = 3; measured 2")
    assert verdict(count("S1").at_least(2), conveyor).passed  # a condition counts the scans it becomes true
    assert not verdict(count("S1").at_most(1), conveyor).passed
    assert count(becomes(all_of("S1", "D1"))).describe() == "number of times S1 and D1 becomes true"


def test_spacing(conveyor):
    assert verdict(spacing(rises("S1")).between("5ms", "5 scans"), conveyor).message == "measured 5 ms"
    v = verdict(spacing(rises("S1")).at_most("4ms"), conveyor)
    assert v.message == "expected every time between successive 'S1 rises' at most 4 ms; measured 5 ms (at 2 ms)"
    assert (v.at_ns, v.window) == (2 * MS, (2 * MS, 7 * MS))
    v = verdict(spacing(rises("S2")).at_least("1ms"), conveyor)  # one rise: nothing to measure
    assert (v.passed, v.message) == (
        False,
        "expected every time between successive 'S2 rises' at least 1ms; there was nothing to measure",
    )


def test_durations(conveyor):
    assert verdict(durations("D1").equals("3ms"), conveyor).message == "measured 3 ms"  # the last one is open
    assert verdict(durations("D1", include_last=True).equals("3 scans"), conveyor).message == "measured 3 ms, 3 ms"
    assert verdict(durations(off("S2")).at_least("3ms"), conveyor).message == "measured 5 ms"
    v = verdict(durations(off("S2")).at_most("3ms"), conveyor)
    assert (v.passed, v.message) == (
        False,
        "expected every time not S2 stays true at most 3 ms; measured 5 ms (at 0 ns)",
    )


def test_durations_failure_names_the_time():
    tr = make_trace({"D1": [1, 1, 0, 1, 0, 0]})
    v = verdict(durations("D1").at_least("2ms"), tr)
    assert v.message == "expected every time D1 stays true at least 2 ms; measured 1 ms (at 3 ms)"
    assert (v.at_ns, v.window) == (3 * MS, (3 * MS, 4 * MS))


def test_duty(conveyor):
    assert verdict(duty("D1").between(0.6, 0.6), conveyor).message == "measured 0.6"
    assert verdict(duty("D1", start="5ms").equals(0.6), conveyor).passed  # rows 5..9: 3 of 5
    v = verdict(duty("D1", start="0ms", end="5ms").at_most(0.5), conveyor)
    assert (v.passed, v.message) == (False, "expected fraction of time D1 at most 0.5; measured 0.6")


def test_final_value_at_and_numbers():
    tr = make_trace({"CV": [0, 1, 2, 2, 3], "D1": [0, 0, 1, 1, 0]}, types={"CV": "int"})
    assert verdict(final("CV").equals(3), tr).message == "measured 3"
    v = verdict(final("CV").equals(4), tr)
    assert (v.passed, v.message, v.at_ns) == (False, "expected CV at the end = 4; measured 3 (at 4 ms)", 4 * MS)
    assert verdict(value_at("CV", "2ms").equals(2), tr).passed  # an input-like column: row 2
    assert verdict(value_at("D1", "3ms").equals(1), tr).passed  # an output: the scan that ended at 3 ms
    v = verdict(value_at("D1", "2ms").equals(1), tr)
    assert v.message == "expected D1 at 2ms = 1; measured 0 (at 2 ms)"
    assert verdict(never(value("CV") > 3), tr).passed
    v = verdict(never(value("CV") >= 2), tr)
    assert v.message == "expected never CV >= 2; it held in the scan at 2 ms (CV=2)"
    assert verdict(always(value("CV") <= value("CV")), tr).passed


def test_measure():
    tr = make_trace({"S1": [0, 1, 0, 1], "D1": [0, 1, 0, 1]})
    check = measure("rises of D1 minus rises of S1", lambda t: len(t.rises("D1")) - len(t.rises("S1")), "D1", "S1")
    v = verdict(check.equals(0), tr)
    assert (v.passed, v.message, v.signals) == (True, "measured 0", ["D1", "S1"])
    v = verdict(measure("gaps", lambda t: [1.0, 5.0]).at_most(2), tr)
    assert (v.passed, v.message) == (False, "expected gaps at most 2; measured 5")
    v = verdict(measure("nothing", lambda t: None).at_most(2), tr)
    assert v.message == "expected nothing at most 2; there was nothing to measure"
    v = verdict(measure("per reset", lambda t: [0.0, None]).equals(0), tr)  # a None item fails, not crashes
    assert (v.passed, v.message) == (False, "expected per reset = 0; measured nothing")


# -- conditions ----------------------------------------------------------------------------------------------


def test_conditions_describe_and_evaluate(conveyor):
    assert any_of("S1", not_("D1")).describe() == "S1 or not D1"
    assert (~all_of("S1", "S2")).describe() == "not (S1 and S2)"
    assert same("D1", "S1").describe() == "D1 == S1"
    assert (value("CV") != 0).describe() == "CV != 0"
    assert verdict(always(any_of("S1", not_("S1"))), conveyor).passed
    assert verdict(never(~any_of("S1", not_("S1"))), conveyor).passed
    v = verdict(always(same("D1", "S1")), conveyor)
    assert v.message == "expected always D1 == S1; it failed in the scan at 4 ms (D1=TRUE, S1=FALSE)"
    with pytest.raises(ConfigurationError, match="expected a condition such as 'D1'"):
        never(3)


# -- spans ------------------------------------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("text", "ns", "scans", "at_1ms", "at_10ms"),
    [
        ("10s + 2 scans", 10_000_000_000, 2.0, 10_002_000_000, 10_020_000_000),
        ("1 scan", 0, 1.0, 1_000_000, 10_000_000),
        ("2 scans", 0, 2.0, 2_000_000, 20_000_000),
        ("0.5s - 1 scan", 500_000_000, -1.0, 499_000_000, 490_000_000),
        ("1min", 60_000_000_000, 0.0, 60_000_000_000, 60_000_000_000),
        ("250 ms", 250_000_000, 0.0, 250_000_000, 250_000_000),
    ],
)
def test_span_parsing(text, ns, scans, at_1ms, at_10ms):
    span = Span.parse(text)
    assert (span.ns, span.scans, str(span)) == (ns, scans, text)
    assert (span.resolve(1_000_000), span.resolve(10_000_000)) == (at_1ms, at_10ms)


def test_span_from_an_integer_and_bad_spans():
    assert Span.parse(5) == Span(5, 0, "5 ns")
    with pytest.raises(ConfigurationError, match=r"^duration '3 parsecs': unknown unit 'parsecs'; use s, ms, us"):
        Span.parse("3 parsecs")
    for bad in ("", "1 scan foo", "10s +", "T#1s"):
        with pytest.raises(ConfigurationError, match=r"^cannot read duration .*; write e.g. '1 scan', '500ms'"):
            Span.parse(bad)
    with pytest.raises(ConfigurationError, match=r"^a duration is written like '10s', '1 scan' or '10s \+ 2 scans'"):
        Span.parse(1.5)
    with pytest.raises(ConfigurationError, match="unknown unit 'parsecs'"):
        rises("D1").within("2 parsecs")


def test_scan_spans_follow_the_cycle_time(conveyor):
    slow = make_trace(CONVEYOR)
    slow.meta["cycle_ns"] = 10 * MS  # "1 scan" is now 10 ms
    late = make_trace(LATE)
    assert not verdict(rises("D1").within("1 scan").after(rises("S1")), late).passed
    late.meta["cycle_ns"] = 2 * MS
    assert verdict(rises("D1").within("1 scan").after(rises("S1")), late).passed
    assert verdict(never("D1").for_more_than("1 scan"), slow).passed


# -- static checks ------------------------------------------------------------------------------------------------


def analysis_of(program: str):
    cpu = CPU({"S1": Tag("%I0.0"), "S2": Tag("%I0.1"), "D1": Tag("%Q0.0")}, program)
    return cpu.compiled.analysis


WITH_SET = "def OB1(t):\n    if t.S1:\n        t.D1 = True\n    if t.S2:\n        t.D1 = False\n"
WITHOUT_SET = "def OB1(t):\n    t.D1 = (t.S1 or t.D1) and not t.S2\n"


def test_program_uses_no_set():
    empty = make_trace({"D1": [0]})
    check = program_uses_no("SET")
    assert check.describe() == "the program uses no SET coils"
    v = verdict(check, empty, analysis_of(WITH_SET))
    assert (v.passed, v.message) == (False, "expected the program uses no SET coils; SET coils: t.D1 (line 3)")
    v = verdict(program_uses_no("RESET"), empty, analysis_of(WITH_SET))
    assert (v.passed, v.message) == (False, "expected the program uses no RESET coils; RESET coils: t.D1 (line 5)")
    v = verdict(check, empty, analysis_of(WITHOUT_SET))
    assert (v.passed, v.message) == (True, "the program uses no SET coils")
    assert verdict(program_uses_no("EDGE"), empty, analysis_of(WITH_SET)).passed
    v = verdict(check, empty, None)
    assert (v.passed, v.message) == (False, "the program could not be analysed")


# -- evaluate_all, names and points ------------------------------------------------------------------------------


def test_a_check_that_raises_becomes_a_failed_verdict(conveyor):
    results = evaluate_all(
        [
            never("NOPE"),
            measure("boom", lambda t: 1 / 0).equals(0),
            count(rises("D1")).equals(2),
        ],
        conveyor,
    )
    messages = [(v.passed, v.message) for _, v in results]
    assert messages == [
        (
            False,
            "the check could not be evaluated: UnknownTagError: the trace has no signal 'NOPE'; traced: S1, S2, D1",
        ),
        (False, "the check could not be evaluated: ZeroDivisionError: division by zero"),
        (True, "measured 2"),
    ]


def test_named_and_points():
    check = never("D1").named("the belt stays off").points(2.5)
    assert (check.title, check.weight, check.describe()) == ("the belt stays off", 2.5, "never D1")
    assert never("D1").title == "never D1"
