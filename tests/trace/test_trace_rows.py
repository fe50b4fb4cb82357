"""Issue 12: the trace stores a row's values only when they changed (plcsim.trace.rows), and reads back the same
dense float64 table, bit for bit, as converting every row: rows that repeat, then change, read in the middle of
a run, zeros of both signs, values a column's packing cannot hold."""

from __future__ import annotations

import numpy as np
import pytest

from exercises import get
from plcsim import CPU, Int, Simulation, Tag
from plcsim.sim.recorder import Recorder
from plcsim.trace.rows import BLOCK, RunLengthRows
from plcsim.trace.table import TraceTable

NAMES = ["S1", "N", "X"]
TYPES = {"S1": "bool", "N": "int", "X": "real"}


def dense(rows: list[tuple]) -> np.ndarray:
    """What the table held before run lengths: every row converted by numpy."""
    return np.array(rows, dtype=np.float64).reshape(len(rows), -1)


def same_bits(a: np.ndarray, b: np.ndarray) -> bool:
    return a.shape == b.shape and a.tobytes() == b.tobytes()


def test_rows_that_repeat_then_change_read_back_as_every_row_and_only_changes_are_stored():
    table = TraceTable(NAMES, types=TYPES)
    rows = []
    for k in range(3 * BLOCK + 17):  # packs in the middle of a run of equal rows
        values = (k // 1000 % 2 == 1, k // 2500, 0.5 if k < 5000 else 1.5)
        rows.append((k * 1_000_000, (k + 1) * 1_000_000, 1, *values))
        table.add_row(*rows[-1][:3], values)
    stored = table.row_sink().stored
    assert len(table) == len(rows) and stored == 15  # k = 0, 1000, 2000, 2500, 3000, 4000, ..., 7500, ..., 12000
    assert same_bits(table.table, dense(rows))
    assert table.column("N").tolist()[2499:2501] == [0.0, 1.0] and table.rises("S1").tolist()[:2] == [1e9, 3e9]


def test_a_trace_read_while_rows_are_appended_keeps_every_row():
    table = TraceTable(NAMES, types=TYPES)
    rows, seen = [], []
    for k in range(2 * BLOCK + 300):
        values = (k % 700 < 350, k // 900, float(k // 1200))
        rows.append((k * 1_000_000, (k + 1) * 1_000_000, 1 if k % 5 else 30, *values))
        table.add_row(*rows[-1][:3], values)
        if k in (0, 1, 349, 350, 351, 4000, BLOCK, BLOCK + 1):  # a live session reads between two scans
            seen.append(len(table.table))
            assert same_bits(table.table, dense(rows)) and len(table) == len(rows)
    assert seen == [1, 2, 350, 351, 352, 4001, BLOCK + 1, BLOCK + 2]
    assert same_bits(table.table, dense(rows)) and same_bits(table.of_task("OB30").table, dense(rows[::5]))


def test_a_zero_that_changes_sign_is_a_change_the_table_keeps():
    table = TraceTable(NAMES, types=TYPES)
    rows = [(k, k + 1, 1, False, 0, x) for k, x in enumerate([0.0, -0.0, -0.0, 0.0, 0, -0.0])]
    for row in rows:
        table.add_row(*row[:3], row[3:])
    assert table.row_sink().stored == 4  # 0.0 == -0.0 in Python; the int 0 packs as +0.0 like the 0.0 before it
    assert same_bits(table.table, dense(rows))
    assert np.signbit(table.column("X")).tolist() == [False, True, True, False, False, True]


@pytest.mark.parametrize(
    "odd",
    [(None, 0, 0.0), (False, 2.5, 0.0), (300, 0, 0.0), (False, 2**64, 0.0), (2, -(2**63), 1e308), (True, 1, None)],
    ids=["None", "a float in an Int", "300 in a Bool", "past Int64", "extremes", "None in a Real"],
)
def test_a_value_its_column_cannot_pack_is_kept_as_numpy_converts_it(odd):
    table = TraceTable(NAMES, types=TYPES)
    values = [(False, 1, 0.25), (False, 1, 0.25), odd, odd, (False, 1, 0.25), (False, 1, 0.25)]
    rows = [(k, k + 1, 1, *v) for k, v in enumerate(values)]
    for row in rows:
        table.add_row(*row[:3], row[3:])
    assert same_bits(table.table, dense(rows))


def test_a_value_numpy_cannot_convert_fails_the_read_as_it_did():
    table = TraceTable(NAMES, types=TYPES)
    table.add_row(0, 1, 1, (False, 1, 2**1030))
    with pytest.raises(OverflowError):
        np.array([(0, 1, 1, False, 1, 2**1030)], dtype=np.float64)
    with pytest.raises(OverflowError):
        _ = table.table


def test_no_signals_and_times_past_int64_are_rows_too():
    rows = RunLengthRows("")
    for k in range(5):
        rows.add(k, k + 1, 1, ())
    rows.add(2**64, 2**64 + 1, 1, ())  # packs as a tuple, converted as numpy converts it
    assert same_bits(rows.take(), dense([(k, k + 1, 1) for k in range(5)] + [(2**64, 2**64 + 1, 1)]))
    assert len(rows) == 0 and rows.take().shape == (0, 3)


def recorded_and_dense(number: str, scenario: str, seconds: list[str]) -> tuple[Simulation, np.ndarray]:
    """A run of an exercise's reference, read after each of ``seconds``, and its rows as every row converted."""
    exercise = get(number)
    sim = exercise.simulation(exercise.reference.program(), exercise.scenario(scenario), seed=1)
    rows: list[tuple] = []
    row = sim.recorder.row
    sim.cpu.scan_end.add(
        lambda cpu: rows.append((cpu.scan_start_ns, cpu.scan_end_ns, 1, *row(cpu.t.__dict__, cpu.image_in)))
    )
    for duration in seconds:
        sim.run(duration)
        assert same_bits(sim.trace.table, dense(rows))
    return sim, dense(rows)


@pytest.mark.parametrize(("number", "scenario"), [("4.3.5", "three objects"), ("6.3.5", "two moves, three strokes")])
def test_a_recorded_run_read_in_the_middle_is_the_run_read_at_the_end(number, scenario):
    exercise = get(number)
    whole = exercise.simulation(exercise.reference.program(), exercise.scenario(scenario), seed=1)
    whole.run("6s")
    assert whole.trace.row_sink().stored < len(whole.trace) / 2  # most scans change nothing traced
    sim, rows = recorded_and_dense(number, scenario, ["1ms", "1ms", "2s", "1s", "2998ms"])
    assert len(rows) == len(whole.trace) == 6000 and sim.trace.digest() == whole.trace.digest()


def test_an_input_the_recorder_cannot_pack_takes_the_general_path_with_the_same_table():
    cpu = CPU(tags={"S1": Tag("%I0.0"), "N": Tag("%MW10", Int)}, program="def OB1(t):\n    t.N = t.N + 1\n")
    recorder = Recorder(cpu)
    recorder.attach()
    rows = []
    for k, level in enumerate([False, False, 300, 300, None, True, True]):  # a host writes odd levels
        cpu.inputs["S1"] = level
        cpu.scan()
        rows.append((k * 1_000_000, (k + 1) * 1_000_000, 1, level, k + 1))
    assert same_bits(recorder.trace.table, dense(rows))


def test_a_regular_row_the_recorder_cannot_pack_is_kept_as_it_is_with_the_same_table():
    """The rows a co-simulation's fused step writes (the recorder's regular row, after the CPU's fused scan): an
    odd level is kept as a tuple with its whole head, among rows that keep their start alone."""
    cpu = CPU(tags={"S1": Tag("%I0.0"), "N": Tag("%MW10", Int)}, program="def OB1(t):\n    t.N = t.N + 1\n")
    recorder = Recorder(cpu)
    recorder.attach()
    step = cpu.fused_scan(None, recorder.regular_row(1_000_000, 1), recorder.scan_hook)
    rows = []
    for k, level in enumerate([False, False, 300, 300, None, True, True]):
        cpu.inputs["S1"] = level
        assert step(cpu.now + 1_000_000)
        rows.append((k * 1_000_000, (k + 1) * 1_000_000, 1, level, k + 1))
    assert same_bits(recorder.trace.table, dense(rows))


def test_regular_rows_keep_their_start_alone_and_read_back_as_rows_with_whole_heads():
    """A co-simulation's fused step (plcsim.sim.stepping) appends a regular row's start time alone: among rows
    with whole heads (an interrupt's, one past Int64 kept as a tuple), across blocks and a change of the regular
    step, the table is the one of every row added with its head."""
    fused, added = RunLengthRows("bq"), RunLengthRows("bq")
    expected = []
    fused.set_regular(1_000_000, 1)
    for k in range(2 * BLOCK + 50):
        t, values = k * 1_000_000, (k % 300 < 100, k // 1000)
        if k == BLOCK + 7:
            fused.set_regular(2_000_000, 4)  # rows unpacked so far keep the step they were appended with
        duration, task = fused.regular
        if k % 97 == 0 or k == 5:  # an interrupt's row (and one head that packs as a tuple)
            head = (2**64, 2**64 + 1, 30) if k == 5 else (t, t + 500, 30)
            fused.add(*head, values)
        else:
            head = (t, t + duration, task)
            fused.heads.append(t)
            packed = fused.pack_values(*values)
            if packed != fused.last[0]:
                fused.last[0] = packed
                fused.changes.append(len(fused.heads) - 1)
                fused.values.append(packed)
            if len(fused.heads) >= BLOCK:
                fused.pack()
        added.add(*head, values)
        expected.append((*head, *values))
    assert len(fused) == len(expected) and same_bits(fused.take(), dense(expected))
    assert same_bits(added.take(), dense(expected))
