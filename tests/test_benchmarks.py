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
