"""Terminal output: grade reports, run summaries and exercise descriptions, with rich."""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

from rich.cells import cell_len
from rich.console import Console
from rich.markup import escape
from rich.panel import Panel
from rich.table import Table
from rich.text import Text

from plcsim.core.console_table import print_records
from plcsim.core.literals import format_ns
from plcsim.core.untrusted_text import for_terminal
from plcsim.scenario.planning import FAULTS


def print_report(report: Any, console: Console | None = None, *, verbose: bool = False, quiet: bool = False) -> None:
    """A grade report, shortest first: the verdict and the score; the failed checks in the order their first
    violation happened (the earliest is usually the cause), each with its reason; then one line per scenario
    (``verbose``: every check and why each passed one passed), the CPU's stops, the traces, the warnings,
    and the verdict again. ``quiet``: the verdict and the failed checks' names alone.

    Every text that may come from a submission (its file name, error messages, check messages,
    CPU diagnostics, warnings) is printed as plain text, never read as Rich markup, with its control and
    format characters as visible escapes (:func:`~plcsim.core.untrusted_text.for_terminal`): a message
    cannot clear the screen, colour a forged verdict or start a line of its own."""
    console = console or Console()
    title = _one_line(f"{report.exercise} {report.title} — {report.submission}")
    if report.error:
        heading = Text.assemble((_one_line(report.error_kind or "error"), "bold red"), ": ", title)
        console.print(Panel(Text(for_terminal(report.error, newlines=True)), title=heading, border_style="red"))
        console.print(Text.assemble("score ", ("0", "bold"), f" / {report.max_score:g}"))
        if report.grader_failed:
            console.print(Text("this is a fault of the grader or the exercise, not of the submission", "yellow"))
        return
    console.print(Text(title, "bold"))
    console.print(_verdict(report))
    failed = sorted(report.failed(), key=_first_violation)
    for c in failed:
        name = _one_line(f"{c.scenario}: {c.check}")
        if quiet:
            console.print(Text.assemble(_mark(c.status), " ", name))
            continue
        console.print(Text.assemble(_mark(c.status), " ", (name, "bold"), f"\n    {_indented(c.message)}"))
        if c.diagram:
            console.print(Text(f"    timing diagram: {_one_line(c.diagram)}"))
        if c.ladder:
            console.print(Text(f"    ladder at that scan: {_one_line(c.ladder)}"))
    if quiet:
        return
    if verbose:
        _print_check_table(report, console)
    else:
        _print_scenario_lines(report, console)
    for run in report.runs:
        if run.cpu_error:
            said = _one_line(f"{run.scenario}: the CPU stopped: {run.cpu_error}")
            console.print(Text.assemble(("!", "yellow"), f" {said}"))
        if run.rrd:
            rrd = _one_line(run.rrd)
            console.print(Text(f"  trace of {_one_line(run.scenario)}: {rrd} (open with: rerun {rrd})", "dim"))
    for w in report.warnings:
        console.print(Text.assemble(("warning:", "yellow"), f" {_one_line(w)}"))
    console.print(_verdict(report))


def _verdict(report: Any) -> Text:
    verdict = Text("PASSED", "bold green") if report.passed else Text("FAILED", "bold red")
    idle = len(report.not_exercised())
    return Text.assemble(
        verdict,
        "  score ",
        (f"{report.score:g}", "bold"),
        f" / {report.max_score:g}",
        (f"  ({idle} not exercised)", "yellow") if idle else "",
        f"  ({report.elapsed_s:.2f} s)",
    )


def _first_violation(check: Any) -> tuple[float, str, str]:
    """When a failed check was first violated (a check without a window: after every one that has one)."""
    start = check.window[0] if check.window is not None else float("inf")
    return (start, check.scenario, check.check)


def _print_scenario_lines(report: Any, console: Console) -> None:
    """One line per scenario: how many of its checks passed (``-v`` lists them)."""
    for scenario in dict.fromkeys(c.scenario for c in report.checks):
        checks = [c for c in report.checks if c.scenario == scenario]
        passed = sum(c.passed for c in checks)
        statuses = {c.status for c in checks}
        status = "failed" if "failed" in statuses else "not exercised" if "not exercised" in statuses else "passed"
        said = _one_line(f"{scenario}: {passed}/{len(checks)} checks passed")
        console.print(Text.assemble(_mark(status), f" {said}"))


def _print_check_table(report: Any, console: Console) -> None:
    """Every check of every scenario with its points, and why each passed check passed."""
    table = Table(show_lines=False, expand=False)
    table.add_column("scenario")
    table.add_column("check")
    table.add_column("", justify="center")
    table.add_column("points", justify="right")
    for c in report.checks:
        table.add_row(
            Text(_one_line(c.scenario)), Text(_one_line(c.check)), _mark(c.status), f"{c.points:g}/{c.max_points:g}"
        )
    console.print(table)
    for c in report.checks:
        if c.passed:
            said = _one_line(f"{c.scenario}: {c.check}: {c.message}")
            console.print(Text.assemble(("✓", "green"), f" {said}", style="dim"))


def _one_line(text: str) -> str:
    """A text that may come from a submission, on one line, escaped (see :func:`for_terminal`)."""
    return for_terminal(text)


def _indented(text: str) -> str:
    """A message of several lines, escaped, each line after the first indented: none starts a line of the
    report's own (a forged ``PASSED`` at the left margin)."""
    return for_terminal(text, newlines=True).replace("\n", "\n    ")


_MARKS = {"passed": ("✓", "green"), "failed": ("✗", "red"), "not exercised": ("–", "yellow")}
"""The mark of each check status; a check that was not exercised earned nothing but did not fail."""


def _mark(status: str) -> Text:
    return Text(*_MARKS[status])


def print_batch_line(report: Any, console: Console) -> None:
    """One line of a batch: the mark, the file name, the score and the first line of the error."""
    from pathlib import Path

    mark = Text("✓", "green") if report.passed else Text("✗", "red")
    first = (report.error or "").strip().splitlines()[:1]
    why = f"  {_one_line(report.error_kind or '')}: {_one_line(first[0]) if first else ''}" if report.error else ""
    name = _one_line(Path(report.submission).name)
    console.print(Text.assemble(mark, f" {name}: {report.score:g}/{report.max_score:g}{why}"))


LIST_TITLE = "plcsim exercises (STU textbook, chapter 4.3)"


def print_exercise_list(exercises: Sequence[Any], console: Console | None = None, *, title: str = LIST_TITLE) -> None:
    rows = []
    for ex in exercises:
        rig = ex.plant_name or (ex.rig().name if ex.rig is not None else "-")
        sols = ", ".join(s.name for s in ex.solutions)
        rows.append([ex.number, ex.slug, ex.title, rig, str(len(ex.scenarios)), sols])
    columns = ["number", "slug", "title", "rig", "scenarios", "solutions"]
    print_records(console or Console(), columns, rows, title=title)


def print_exercise(ex: Any, console: Console | None = None, *, solutions: bool = False) -> None:
    """An exercise as a student reads it: the task, the I/O table, data blocks, scenarios, the requirements of
    the task each check grades, and the checks; with ``solutions`` (for instructors) also the programs shipped
    with it, what each shows, and the exercise's notes (they give the reference's logic away)."""
    console = console or Console()
    heading = f"{ex.number} {ex.title}" + (f" ({ex.title_sk})" if ex.title_sk else "")
    if cell_len(heading) + 6 <= console.width:  # in the panel's border, where it fits whole
        console.print(Panel(Text(ex.task), title=Text(heading, style="bold"), expand=False))
    else:  # above the panel: a border would cut it
        console.print(Text(heading, style="bold"), soft_wrap=True)
        console.print(Panel(Text(ex.task), expand=False))
    columns = ["tag", "gloss", "type", "address", "direction", "wiring", "comment"]
    rows = [[row[c] for c in columns] for row in ex.describe_io()]
    print_records(console, columns, rows, title="I/O table")
    for name, db in ex.dbs.items():
        members = [
            [key, member.type.name, "" if member.start is None else str(member.start), _retained(db, member)]
            for key, member in db.members.items()
        ]
        print_records(console, ["member", "type", "start", "retain"], members, title=f"data block {name}")
    console.print("[bold]Scenarios[/]")
    for s in ex.scenarios:
        said = f": {s.description}" if s.description else ""
        console.print(Text(f"  • {s.name} ({format_ns(s.duration_ns)}){said}"))
        for left, then in s.outside.items():
            what = "injects a fault" if left == FAULTS else f'leaves "{left}"'
            console.print(Text(f'      {what}; the task says: "{then}"'))
    _print_conditions(ex, console)
    _print_requirements(ex, console)
    if solutions:
        from plcsim.exercise.catalog import command_name

        console.print(
            f"[bold]Shipped programs[/] (grade one with: plcsim grade {escape(command_name(ex))} --solution NAME)"
        )
        for s in ex.solutions:
            console.print(Text(f"  • {s.name} [{s.kind}]: {s.explanation}"))
        if ex.notes:
            console.print(Panel(Text(ex.notes), title="notes for instructors", expand=False, border_style="dim"))


def _retained(db: Any, member: Any) -> str:
    return "yes" if member.retain or db.retain else ""


def _print_conditions(ex: Any, console: Console) -> None:
    """What the task assumes of the operator and the machine: no scenario leaves it without saying so above."""
    if ex.conditions:
        console.print("[bold]The task assumes[/] (a scenario that leaves it says so above, with the task's words)")
        for condition in ex.conditions:
            console.print(Text(f'  • "{condition.words}"'))


def _print_requirements(ex: Any, console: Console) -> None:
    """The task's requirements, each with the checks that grade it; then the checks that name none."""
    requirements = ex.requirement_list()
    if requirements:
        console.print("[bold]Requirements[/] (the words of the task each check grades)")
        for k, (words, checks) in enumerate(requirements, 1):
            console.print(Text(f'  {k}. "{words}"'))
            for c in checks:
                console.print(Text(f"       • {c.name}" + (f"  ({', '.join(c.scenarios)})" if c.scenarios else "")))
    rest = [c for c in ex.checks if not c.requirement]
    if rest:
        console.print("[bold]Checks[/]" if not requirements else "[bold]Other checks[/]")
        for c in rest:
            console.print(Text(f"  • {c.name}" + (f"  ({', '.join(c.scenarios)})" if c.scenarios else "")))


def print_run_summary(sim: Any, wall_s: float, console: Console | None = None, *, events: int = 12) -> None:
    console = console or Console()
    cpu = sim.cpu
    rtf = (sim.now / 1e9) / wall_s if wall_s > 0 else float("inf")
    console.print(
        f"simulated {format_ns(sim.now)} in {wall_s:.2f} s wall ({rtf:,.0f}× real time), "
        f"{cpu.scan_count} scans, CPU {cpu.mode}"
    )
    shown = [e for e in sim.trace.events if e.source in ("plant", "cpu", "scenario")]
    if shown:
        console.print(f"[bold]events[/] ({len(shown)}; first {min(events, len(shown))}):")
        for e in shown[:events]:
            console.print(Text(f"  {_one_line(str(e))}"), highlight=False)
    if cpu.error:
        console.print(Text.assemble(("the CPU stopped:", "red"), f" {_one_line(str(cpu.error))}"))
    for w in cpu.warnings:
        console.print(Text.assemble(("warning:", "yellow"), f" {_one_line(w)}"))
