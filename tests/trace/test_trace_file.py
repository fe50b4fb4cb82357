"""A saved trace (``plcsim run --trace out.npz``) names every column in the file, and reads back bit for bit."""

from __future__ import annotations

import json

import numpy as np

from plcsim.trace.facade import Trace
from plcsim.trace.table import TraceTable


def _small_trace() -> Trace:
    trace = Trace(
        ["S1", "COUNT", "LEVEL"],
        kinds={"S1": "input", "COUNT": "memory", "LEVEL": "analog"},
        types={"S1": "bool", "COUNT": "int", "LEVEL": "real"},
        task_numbers={"OB1": 1, "OB30": 30},
    )
    for k in range(5):
        trace.add_row(k * 1_000_000, k * 1_000_000 + 400_000, 1, (k % 2 == 1, -32768 + k, 0.25 * k))
    trace.add_row(2_500_000, 2_600_000, 30, (True, 7, 1.5))
    return trace


def test_every_column_is_named_in_the_file_with_its_type(tmp_path):
    path = _small_trace().save(tmp_path / "run.npz")
    with np.load(path) as data:
        assert sorted(data.files) == ["end_ns", "header", "start_ns", "table", "task"]
        table = data["table"]
        assert table.dtype.names == ("S1", "COUNT", "LEVEL")
        assert (table["S1"].dtype, table["COUNT"].dtype, table["LEVEL"].dtype) == (np.bool_, np.int64, np.float64)
        assert table["COUNT"].tolist() == [-32768, -32767, -32766, -32765, -32764, 7]
        assert data["task"].tolist() == [1, 1, 1, 1, 1, 30]
        assert data["start_ns"][-1] == 2_500_000 and data["end_ns"][-1] == 2_600_000
        assert json.loads(str(data["header"]))["tasks"] == {"OB1": 1, "OB30": 30}


def test_a_saved_trace_reads_back_bit_for_bit(tmp_path):
    trace = _small_trace()
    again = Trace.load(trace.save(tmp_path / "run.npz"))
    assert again.digest() == trace.digest()
    assert again.table.tobytes() == trace.table.tobytes()


def test_a_trace_saved_by_plcsim_0_1_still_reads(tmp_path):
    """0.1 saved one float64 table whose first three columns (start, end, task) had no names."""
    trace = _small_trace()
    header = {"names": trace.names, "kinds": trace.kinds, "types": trace.types, "meta": {}, "events": []}
    path = tmp_path / "old.npz"
    np.savez_compressed(path, table=trace.table, header=np.array(json.dumps(header)))
    assert TraceTable.load(path).table.tobytes() == trace.table.tobytes()
