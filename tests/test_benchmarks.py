"""Smoke test of the benchmark package: ``python -m benchmarks --quick`` runs and speaks JSON lines.

No timing assertions: performance is measured by ``python -m benchmarks``, never by timed tests.
"""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def test_quick_benchmarks_print_one_json_figure_per_line():
    proc = subprocess.run(
        [sys.executable, "-m", "benchmarks", "--quick"],
        cwd=ROOT,
        capture_output=True,
        text=True,
        timeout=300,
    )
    assert proc.returncode == 0, proc.stderr
    lines = proc.stdout.splitlines()
    assert lines, proc.stderr
    figures = {}
    for line in lines:
        record = json.loads(line)
        assert {"figure", "value", "unit"} <= record.keys(), line
        figures[record["figure"]] = record
    for name in ("plc_scans_per_s", "plc_us_per_scan", "plc_compile_ms", "plc_equivalence"):
        assert name in figures
    assert figures["plc_scans_per_s"]["value"] > 0
    for name in ("pyrung_scans_per_s", "plcsim_vs_pyrung_ratio"):  # measured, or skipped with a reason
        assert name in figures
        assert figures[name]["value"] is not None or figures[name]["skipped"]
    equivalence = figures["plc_equivalence"]
    assert equivalence["value"] is True, equivalence
    assert equivalence["plcsim_digest"] == equivalence["reference_digest"]
    assert figures["mutation_score_4.3.1"]["value"] == 1.0  # the one mutant of 4.3.1 is killed
    assert figures["tecomat_scans_per_s"]["value"] > 0 and figures["tecomat_scans_per_s"]["s7_scans_per_s"] > 0
    for form in ("mech", "python"):  # the PLC836 mechanisms beside the S7 form of the same logic
        assert figures[f"mechanisms_{form}_scans_per_s"]["s7_scans_per_s"] > 0
    digests = figures["solutions_trace_digest"]
    assert len(digests["value"]) == 64 and digests["runs"] > 0
    for name in ("pyrung_kernel_scans_per_s", "plcsim_vs_pyrung_kernel_ratio"):
        assert name in figures
        assert figures[name]["value"] is not None or figures[name]["skipped"]
    assert figures["inlined_python_scans_per_s"]["same_outputs"] is True
    assert figures["plc_vs_inlined_ratio"]["value"] > 0
    assert 0 < figures["plc_vs_inlined_opcode_ratio"]["value"] < 1  # plcsim runs more opcodes than the ceiling
    for workload in ("shuttle", "sorter"):
        assert figures[f"cosim_overhead_vs_handwritten_ratio_{workload}"]["same_rows"] is True


def test_the_inlined_anchor_gives_the_reference_rows_scan_for_scan():
    """The hand-inlined ceiling computes what plcsim and the reference compute (not a cheaper program)."""
    from benchmarks import equivalence, inlined, workload

    sched = workload.build_schedule(5_000)
    assert inlined.inlined_rows(sched) == equivalence.reference_rows(sched)


def test_the_hand_written_cosim_baselines_write_plcsims_trace_rows():
    """Each baseline, replaying the co-simulation's scenario calls, writes the rows plcsim's trace holds."""
    from benchmarks import cosim, handwritten

    for workload, _, rig in cosim.WORKLOADS:
        if workload not in handwritten.BASELINES:
            continue
        _, sim, log = cosim._cosim(workload, 5)
        rows, _ = handwritten.run_baseline(workload, rig, sim.now // 1_000_000_000, log, sim.dt_ns)
        assert len(rows) == len(sim.trace) > 0
        assert handwritten.same_rows(rows, sim.trace), workload
        assert rows[:, 6 if workload == "sorter" else 2].any()  # the belt ran: the program did something
