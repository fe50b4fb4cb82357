"""The grade report's ladder: for a failed check, beside its timing diagram, the networks that write the
check's signals, drawn with the values of the scan where it failed (from the trace)."""

from __future__ import annotations

import xml.etree.ElementTree as ET
from pathlib import Path

from exercises import get
from plcsim.grading.grader import grade, grade_sandboxed
from plcsim.ladder.snapshot import TraceTags, networks_writing


def _coil_power(svg: str, operand: str) -> list[str]:
    root = ET.fromstring(svg)
    return [g.get("data-power") for g in root.iter("{http://www.w3.org/2000/svg}g") if g.get("data-operand") == operand]


def test_a_failed_check_gets_the_ladder_of_the_networks_writing_its_signals_at_the_failing_scan(tmp_path):
    exercise = get("4.3.7")
    solution = exercise.solution("wrong-scan-order")
    report = grade(exercise, solution.path, plots_dir=tmp_path, scenarios=["jam"])
    failed = next(c for c in report.failed() if c.check == "ACK clears ALARM within 1 scan")
    assert failed.diagram and failed.ladder and failed.ladder.endswith("-ladder.svg")
    svg = Path(failed.ladder).read_text(encoding="utf-8")
    titles = [
        t.text
        for t in ET.fromstring(svg).iter("{http://www.w3.org/2000/svg}text")
        if (t.text or "").startswith("Network")
    ]
    assert [t.split(":")[0] for t in titles] == ["Network 3", "Network 4"]  # the two networks that write ALARM
    assert _coil_power(svg, "ALARM")[-1] == "true"  # ACK's rung has power in that scan: its R ALARM is lit
    sandboxed = grade_sandboxed(exercise, solution.path, plots_dir=tmp_path / "sandboxed", scenarios=["jam"])
    assert next(c for c in sandboxed.failed() if c.check == failed.check).ladder


def test_trace_values_are_read_at_the_instant_and_what_was_not_recorded_stays_unknown():
    exercise = get("4.3.7")
    program = exercise.reference.program()
    assert networks_writing(program, ["ALARM"]) == {"watchdog", "acknowledge"}
    assert networks_writing(program, ["TON_A.Q"]) == {"watchdog"}

    class Recorded:
        names = ["S1", "DATA.X", "TON_A.Q"]

        def value_at(self, name, t_ns):
            return {"S1": t_ns > 5, "DATA.X": 3, "TON_A.Q": True}[name]

    tags = TraceTags(Recorded(), 10)
    assert tags.S1 is True and tags.DATA.X == 3 and tags.TON_A.member("Q") is True
    assert tags.TON_A.member("ET") is None
    try:
        bool(tags.NOT_RECORDED)
    except LookupError:
        pass
    else:
        raise AssertionError("an unrecorded signal must not read as a value")
