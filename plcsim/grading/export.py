"""Export a grade's runs as files: rerun recordings, ``.npz`` traces and timing diagrams of failed checks.

The exporters run in the grader, from the traces the run returned (in this process or validated from
the sandbox's child), after the checks: a grade never depends on which files were asked for.
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path
from typing import Any

from plcsim.exercise.model import Exercise
from plcsim.frontends.python.program import Program
from plcsim.grading.report import CheckResult, Report
from plcsim.grading.run_result import RunResult


def export(
    exercise: Exercise,
    runs: Sequence[RunResult],
    report: Report,
    *,
    rrd_dir: str | Path | None = None,
    plots_dir: str | Path | None = None,
    traces_dir: str | Path | None = None,
    program: Any = None,
) -> None:
    """Write the recordings, traces and failure diagrams asked for; file names carry the exercise, the
    submission and the scenario, so that the students of a batch never overwrite each other's files.

    Beside a failed check's timing diagram, for a Python ``program``: the ladder of the networks that write
    the check's signals, drawn with the values of the scan where it failed (``result.ladder``)."""
    by_name = {run.scenario: run for run in runs}
    for scenario_run in report.runs:
        run = by_name[scenario_run.scenario]
        stem = f"{exercise.slug}-{_slug(report.student)}-{_slug(run.scenario)}"
        if rrd_dir is not None:
            Path(rrd_dir).mkdir(parents=True, exist_ok=True)
            scenario_run.rrd = str(run.trace.to_rrd(Path(rrd_dir) / f"{stem}.rrd"))
        if traces_dir is not None:
            Path(traces_dir).mkdir(parents=True, exist_ok=True)
            scenario_run.trace_npz = str(run.trace.save(Path(traces_dir) / f"{stem}.npz"))
        if plots_dir is not None:
            for result in report.checks:
                if not result.passed and result.scenario == run.scenario and len(run.trace):
                    result.diagram = _diagram(run, result, Path(plots_dir) / f"{stem}-{_slug(result.check)}.png")
                    if isinstance(program, Program):
                        path = Path(plots_dir) / f"{stem}-{_slug(result.check)}-ladder.svg"
                        try:
                            result.ladder = _ladder(program, exercise, run, result, path)
                        except Exception as exc:  # noqa: BLE001 - a picture that fails must never change a grade
                            report.warnings.append(f"no ladder for {result.check}: {type(exc).__name__}: {exc}")


def _slug(text: str) -> str:
    return "".join(ch if ch.isalnum() else "_" for ch in text)[:60].strip("_")


def _ladder(program: Program, exercise: Exercise, run: RunResult, result: CheckResult, path: Path) -> str | None:
    """The networks that write the failed check's signals, with the values of the scan where it failed."""
    from plcsim.ladder.snapshot import networks_writing
    from plcsim.ladder.view import Ladder

    names = networks_writing(program, result.signals)
    if not names:
        return None
    at = result.at_ns if result.at_ns is not None else (result.window[0] if result.window else run.simulated_ns)
    picture = Ladder(
        program, exercise.tag_table(), title=f"{result.scenario}: {result.check} — the scan at {at / 1e9:g} s"
    )
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(picture.at_trace(run.trace, at, names), encoding="utf-8")
    return str(path)


def _diagram(run: RunResult, result: CheckResult, path: Path) -> str | None:
    try:
        from plcsim.trace.plot import save_timing_diagram
    except ImportError:
        return None
    path.parent.mkdir(parents=True, exist_ok=True)
    signals = [s for s in result.signals if s in run.trace] or None
    start = end = None
    if result.window is not None:
        first = min(result.window[0], result.at_ns if result.at_ns is not None else result.window[0])
        margin = max(1_000_000_000, (result.window[1] - first) // 4)
        start = max(0, first - margin)
        end = result.window[1] + margin
    highlight = (result.window[0], result.window[1], result.check) if result.window else None
    save_timing_diagram(
        run.trace, path, signals, start=start, end=end, highlight=highlight, title=f"{result.scenario}: {result.check}"
    )
    return str(path)
