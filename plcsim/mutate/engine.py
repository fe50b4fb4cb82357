"""Mutation testing of an exercise's checks: plant the slips students make into the reference
solution and see whether the checks catch each one.

The mutants come from the operators of the reference's language, chosen by its suffix in :data:`LANGUAGES`:
:mod:`plcsim.mutate.python` for a Python program (S7), :mod:`plcsim.mutate.il` for a Tecomat instruction
list (``.il``, loaded through the Tecomat front end), :mod:`plcsim.mutate.mech` for PLC836 mechanisms
(``.mech``); all are graded and classified alike.

Each mutant is graded as :func:`plcsim.grading.grader.grade` grades it (in this process: the mutants derive
from the trusted reference) on seeds 1..N. It is **killed** if some check fails on some seed that the
reference passes on that seed, **stillborn** if it does not load (counted apart, not as killed).
A surviving mutant is **equivalent** if its behaviour equals the reference's in every scenario and
seed: the same changes of every tag of the exercise's I/O table and data blocks at the same times
and the same events (the program's own tags, such as a timer's ET, and the edge memory bits the
reference names are the edge and timer instructions' bookkeeping, which no check reads; the CPU's
clock and system bits do not depend on the program). A survivor's report names the tags that
differ. Equivalent means "no scenario tells it apart": read those too, a scenario may be missing.
A survivor the exercise declares a correct program by the spec's words (its ``spec_equivalent``,
with the reason: the falling edge of Clock_1Hz is a one-second pulse too) is **explained**; a
declaration that names no mutant is an error (:class:`~plcsim.core.errors.ExerciseError`), and one whose
mutant a check kills is reported as misleading (a check is stricter than the spec, or the
declaration is wrong). Score = killed / (killed + survived): explained mutants are left out.
"""

from __future__ import annotations

import ast
import hashlib
import json
import multiprocessing
import sys
import time
from collections.abc import Callable, Iterable, Iterator, Sequence
from concurrent.futures import ProcessPoolExecutor
from dataclasses import asdict, dataclass, field
from pathlib import Path, PurePath
from typing import Any

import numpy as np

from plcsim.controllers.loaded import SourceProgram
from plcsim.controllers.s7.cpu import CLOCK_BITS, SYSTEM_BITS
from plcsim.core.errors import ExerciseError, PlcError, did_you_mean
from plcsim.exercise.model import Exercise
from plcsim.frontends.python.program import Program
from plcsim.grading.report import NOT_EXERCISED, Report
from plcsim.grading.run import load_error_kind, run_scenarios
from plcsim.grading.run_result import RunResult
from plcsim.grading.scoring import evaluate, failure_report
from plcsim.mutate import il, mech, python
from plcsim.mutate.mutant import Mutant

KILLED, SURVIVED, EXPLAINED, EQUIVALENT, STILLBORN = "killed", "survived", "explained", "equivalent", "stillborn"
STATUSES = (KILLED, SURVIVED, EXPLAINED, EQUIVALENT, STILLBORN)

_CPU_BITS = {name for _, name, _ in CLOCK_BITS} | {name for _, name in SYSTEM_BITS}


@dataclass(frozen=True)
class Language:
    """The mutation operators of one language: its programs as an error names them, the mutants of an
    exercise's reference, and a mutant loaded as a program (PlcError if it does not load)."""

    name: str
    mutants: Callable[[Exercise], list[Mutant]]
    load: Callable[[str, str, Exercise], SourceProgram]


LANGUAGES: dict[str, Language] = {
    ".py": Language("a Python (S7)", python.reference_mutants, python.load_mutant),
    ".il": Language("an instruction-list (Tecomat, .il)", il.reference_mutants, il.load_mutant),
    ".mech": Language("a PLC836 mechanisms (.mech)", mech.reference_mutants, mech.load_mutant),
}
"""The reference's suffix -> the operators of its language: a new language is one more line."""


# --------------------------------------------------------------------------------------------
# Grading mutants
# --------------------------------------------------------------------------------------------


@dataclass
class Outcome:
    """What became of one mutant: its status and why (the check that killed it, the load error), and
    the exercise's reason when it declares the mutant a correct program."""

    mutant: Mutant
    status: str
    detail: str = ""
    reason: str = ""


@dataclass
class MutationReport:
    """The mutants of one exercise's reference and their outcomes."""

    exercise: str
    title: str
    seeds: list[int]
    outcomes: list[Outcome] = field(default_factory=list)
    reference_failures: list[str] = field(default_factory=list)
    misleading: list[str] = field(default_factory=list)
    elapsed_s: float = 0.0

    def count(self, status: str) -> int:
        return sum(o.status == status for o in self.outcomes)

    def of(self, status: str) -> list[Outcome]:
        return [o for o in self.outcomes if o.status == status]

    @property
    def score(self) -> float | None:
        """Killed / mutants that change behaviour (None when no mutant does)."""
        changed = self.count(KILLED) + self.count(SURVIVED)
        return self.count(KILLED) / changed if changed else None

    def to_dict(self) -> dict[str, Any]:
        data = asdict(self)
        data["score"] = self.score
        data["counts"] = {s: self.count(s) for s in STATUSES}
        for o in data["outcomes"]:
            o["mutant"]["label"] = f"line {o['mutant']['line']}: {o['mutant']['description']}"
        return data

    def to_json(self, path: str | Path | None = None) -> str:
        text = json.dumps(self.to_dict(), indent=2)
        if path is not None:
            Path(path).write_text(text, encoding="utf-8")
        return text


def exercise_mutants(exercise: Exercise) -> list[Mutant]:
    """The mutants of an exercise's reference solution, by the operators of its language (:data:`LANGUAGES`).

    Raises :class:`~plcsim.core.errors.ExerciseError` if the exercise's ``spec_equivalent`` names a mutant
    the reference does not have (see :func:`declared_equivalents`).
    """
    path = Path(exercise.reference.path)
    language = LANGUAGES.get(path.suffix)
    if language is None:
        known = " nor ".join(lang.name for lang in LANGUAGES.values())
        raise PlcError(
            f"exercise {exercise.number}: its reference {path.name} is neither {known} program; "
            f"mutation testing derives mutants of these languages only"
        )
    mutants = language.mutants(exercise)
    declared_equivalents(exercise, mutants)
    return mutants


def declared_equivalents(exercise: Exercise, mutants: Sequence[Mutant]) -> dict[tuple[int, str], str]:
    """The exercise's ``spec_equivalent`` matched to ``mutants`` (its reference's): {(line, description): reason}.

    A key is a mutant's description, or ``"line N: description"``. A key that matches no mutant is
    stale (the reference or an operator changed) and one that matches several is ambiguous: both
    raise :class:`~plcsim.core.errors.ExerciseError` naming the exercise's file and line.
    """
    out: dict[tuple[int, str], str] = {}
    problems = []
    for key, reason in exercise.spec_equivalent.items():
        matches = [m for m in mutants if key in (m.description, str(m))]
        if len(matches) == 1:
            out[matches[0].line, matches[0].description] = reason
        elif not matches:
            hint = did_you_mean(key, [m.description for m in mutants])
            problems.append(f"spec_equivalent names {key!r}, which is no mutant of the reference{hint}")
        else:
            lines = ", ".join(str(m.line) for m in matches)
            problems.append(f"spec_equivalent {key!r} names the mutants of lines {lines}: write 'line N: {key}'")
    if problems:
        listed = "; ".join(problems)
        raise ExerciseError(f"{exercise.defined_at}: exercise {exercise.number}: {listed}", problems)
    return out


def mutate_exercise(
    exercise: Exercise,
    *,
    seeds: int = 3,
    jobs: int = 1,
    mutants: Sequence[Mutant] | None = None,
    progress: Callable[[int, int, Outcome], None] | None = None,
) -> MutationReport:
    """Grade every mutant of the exercise's reference on seeds 1..``seeds``; ``jobs`` mutants at a time."""
    started = time.perf_counter()
    every = exercise_mutants(exercise)
    reasons = declared_equivalents(exercise, every)
    chosen = list(mutants) if mutants is not None else every
    job = _Job(exercise, list(range(1, seeds + 1)))
    report = MutationReport(exercise.number, exercise.title, job.seeds, reference_failures=job.reference_failures())
    outcomes: list[Outcome] = []
    for outcome in _map(job, chosen, jobs):
        outcomes.append(outcome)
        if progress is not None:
            progress(len(outcomes), len(chosen), outcome)
    report.outcomes = sorted(outcomes, key=lambda o: o.mutant.number)
    for outcome in report.outcomes:
        _explain(outcome, reasons.get((outcome.mutant.line, outcome.mutant.description)), report.misleading)
    report.elapsed_s = time.perf_counter() - started
    return report


def _explain(outcome: Outcome, reason: str | None, misleading: list[str]) -> None:
    """Apply the exercise's declaration to one outcome: a survivor is explained; a killed or
    stillborn mutant makes the declaration misleading (an equivalent one stays equivalent)."""
    if reason is None:
        return
    outcome.reason = reason
    if outcome.status == SURVIVED:
        outcome.status = EXPLAINED
    elif outcome.status in (KILLED, STILLBORN):
        misleading.append(
            f"{outcome.mutant}: declared a correct program ({reason}), but {outcome.status} ({outcome.detail}):"
            " a check is stricter than the spec, or the declaration is wrong"
        )


class _Job:
    """The reference's verdicts and behaviour per seed, and the grading of one mutant against them.

    A mutant runs each scenario once per seed, shortest scenario first: a check it fails there that the
    reference passes kills it at once (most mutants die in the first short scenario); a survivor's
    behaviour is read from the same runs that graded it. The verdicts equal :func:`~plcsim.grading.grader.grade`'s:
    the seed's runs are evaluated together, as a grade evaluates them, before a mutant is called a survivor."""

    def __init__(self, exercise: Exercise, seeds: list[int]):
        self.exercise = exercise
        self.seeds = seeds
        self.reference = exercise.reference.program()
        self.language = LANGUAGES[Path(exercise.reference.path).suffix]
        self.ignore = edge_memories(self.reference) if isinstance(self.reference, Program) else set()
        self._order = sorted(exercise.scenarios, key=lambda s: s.duration_ns)
        self._rank = {s.name: i for i, s in enumerate(exercise.scenarios)}
        self._failed: dict[int, set[str]] = {}
        self._behaviour: dict[tuple[int, str], dict[str, str]] = {}
        for seed in seeds:
            runs: list[RunResult] = []
            report = self._graded(self.reference, seed, runs, kills=None)
            self._failed[seed] = _failures(report)
            self._behaviour |= {(seed, run.scenario): self._behaviour_of(self.reference, run) for run in runs}

    def reference_failures(self) -> list[str]:
        return [f"seed {s}: {f}" for s in self.seeds for f in sorted(self._failed[s])]

    def outcome(self, mutant: Mutant) -> Outcome:
        try:
            program = self.load(mutant)
        except PlcError as exc:
            return Outcome(mutant, STILLBORN, str(exc))
        behaviour: dict[tuple[int, str], dict[str, str]] = {}
        for seed in self.seeds:
            runs: list[RunResult] = []
            report = self._graded(program, seed, runs, kills=self._failed[seed])
            if report.error is not None:
                return Outcome(mutant, STILLBORN, report.error)
            new = sorted(_failures(report) - self._failed[seed])
            if new:
                return Outcome(mutant, KILLED, f"seed {seed}: {new[0]}")
            behaviour |= {(seed, run.scenario): self._behaviour_of(program, run) for run in runs}
        for seed in self.seeds:
            for scenario in self.exercise.scenarios:
                mine, theirs = behaviour[seed, scenario.name], self._behaviour[seed, scenario.name]
                differ = sorted(k for k in mine.keys() | theirs.keys() if mine.get(k) != theirs.get(k))
                if differ:
                    shown = ", ".join(differ[:4]) + (" ..." if len(differ) > 4 else "")
                    return Outcome(
                        mutant,
                        SURVIVED,
                        f"every check passes, but these differ: {shown} (seed {seed}, scenario {scenario.name!r})",
                    )
        return Outcome(mutant, EQUIVALENT, "the same behaviour as the reference in every scenario and seed")

    def load(self, mutant: Mutant) -> SourceProgram:
        """The mutant as a program of the reference's front end (PlcError if it does not load)."""
        return self.language.load(mutant.source, f"<mutant {mutant.number}>", self.exercise)

    def _graded(self, program: SourceProgram, seed: int, runs: list[RunResult], kills: set[str] | None) -> Report:
        """``program`` graded on ``seed`` as :func:`~plcsim.grading.grader.grade` grades it, its runs appended to
        ``runs``. With ``kills`` (the reference's failures), it stops at the first scenario where a check
        fails that the reference passes: that failure is in the grade whatever the other scenarios do
        (a check's verdict in a run depends on that run alone; only "not exercised" looks across runs, so
        it waits for the whole grade)."""
        exercise = self.exercise
        report = Report(exercise.number, exercise.title, getattr(program, "filename", ""), seed=seed)
        analysis = None
        try:
            for scenario in self._order:
                (run,), found = run_scenarios(exercise, program, seed=seed, scenarios=[scenario.name], geometry=False)
                analysis = analysis if analysis is not None else found
                runs.append(run)
                if kills is None or len(runs) == len(self._order):
                    continue
                alone = evaluate(exercise, [run], analysis, Report(exercise.number, exercise.title, report.submission))
                if alone.error is not None:
                    return alone
                if _failures(alone, real_only=True) - kills:
                    alone.checks = [c for c in alone.checks if c.status != NOT_EXERCISED]
                    return alone
        except PlcError as exc:
            return failure_report(report, load_error_kind(exc), str(exc), exercise)
        runs.sort(key=lambda r: self._rank[r.scenario])
        return evaluate(exercise, runs, analysis, report)

    def _behaviour_of(self, program: SourceProgram, run: RunResult) -> dict[str, str]:
        return behaviour(self.exercise, run.trace, run.plant_error or "", self.ignore, getattr(program, "filename", ""))


def _failures(report: Report, *, real_only: bool = False) -> set[str]:
    """The report's failed checks by scenario and name (``real_only``: not those failed as not exercised)."""
    return {
        f"scenario {c.scenario!r}: {c.check}" for c in report.failed() if not (real_only and c.status == NOT_EXERCISED)
    }


def edge_memories(program: Program) -> set[str]:
    """The tags a program names as edge memory (``P(x, "SB1")``): the edge instruction's bookkeeping."""
    out = set()
    for node in ast.walk(program.tree):
        if isinstance(node, ast.Call) and isinstance(node.func, ast.Name):
            k = {"P": 1, "N": 1, "P_TRIG": 1, "N_TRIG": 1, "P_COIL": 2, "N_COIL": 2}.get(node.func.id)
            if k is not None and len(node.args) > k and isinstance(node.args[k], ast.Constant):
                out.add(str(node.args[k].value))
    return out


def behaviour(
    exercise: Exercise, trace: Any, error: str = "", ignore: Iterable[str] = (), filename: str = ""
) -> dict[str, str]:
    """What a check can see of a run, hashed per signal: when each exercise tag changed and to what,
    the events and the CPU's error (tags in ``ignore``, the CPU's clock and system bits left out;
    the program's ``filename`` in a message is read as ``<program>``: a mutant's name is not behaviour)."""
    heads = {row.tag for row in exercise.io} | set(exercise.dbs)
    skip = _CPU_BITS | set(ignore)
    events = json.dumps([asdict(e) for e in trace.events])
    for name in dict.fromkeys((filename, PurePath(filename).name) if filename else ()):  # the trace names the file
        events, error = (text.replace(json.dumps(name)[1:-1], "<program>") for text in (events, error))
    out = {"events": _hash(events.encode()), "CPU error": error}
    for name in trace.names:
        if name.split(".")[0] in heads and name not in skip:
            col = trace.column(name).astype(np.float64)
            changed = np.concatenate(([True], col[1:] != col[:-1])) if len(col) else np.zeros(0, dtype=bool)
            out[name] = _hash(trace.signal_times(name)[changed].tobytes(), col[changed].tobytes())
    return out


def _hash(*chunks: bytes) -> str:
    h = hashlib.sha256()
    for chunk in chunks:
        h.update(chunk)
    return h.hexdigest()


_CURRENT: _Job | None = None  # the job a forked worker inherits (nothing is pickled but the mutant)


def _grade_in_worker(mutant: Mutant) -> Outcome:
    assert _CURRENT is not None
    return _CURRENT.outcome(mutant)


def _map(job: _Job, mutants: list[Mutant], jobs: int) -> Iterator[Outcome]:
    """The mutants' outcomes, in order: ``jobs`` forked workers on Linux, one after another elsewhere (Windows
    cannot fork; macOS can, but a fork of a process with threads may crash there, so Python spawns by default)."""
    global _CURRENT
    if jobs <= 1 or len(mutants) < 2 or not sys.platform.startswith("linux"):
        yield from map(job.outcome, mutants)
        return
    _CURRENT = job
    try:
        with ProcessPoolExecutor(max_workers=jobs, mp_context=multiprocessing.get_context("fork")) as pool:
            yield from pool.map(_grade_in_worker, mutants)
    finally:
        _CURRENT = None


# --------------------------------------------------------------------------------------------
# Terminal output
# --------------------------------------------------------------------------------------------


def print_mutation_report(report: MutationReport, console: Any) -> None:
    """The score, the surviving mutants (where the checks are weak) and the equivalent ones."""
    from rich.table import Table
    from rich.text import Text

    console.print(Text(f"mutation testing of {report.exercise} {report.title}", style="bold"))
    console.print(
        Text(
            f"{len(report.outcomes)} mutants of the reference, graded on seed{'s' if len(report.seeds) > 1 else ''} "
            f"{', '.join(map(str, report.seeds))} in {report.elapsed_s:.1f} s"
        )
    )
    if report.reference_failures:
        console.print(Text("the reference itself fails (these failures do not kill a mutant):", style="yellow"))
        for line in report.reference_failures:
            console.print(Text(f"  {line}"))
    for status, title, style in (
        (SURVIVED, "surviving mutants (behave differently, pass every check)", "red"),
        (EXPLAINED, "explained mutants (correct programs by the spec's words, not counted)", "cyan"),
        (EQUIVALENT, "equivalent mutants (no scenario tells them apart)", "yellow"),
        (STILLBORN, "mutants that do not load (not counted)", "dim"),
    ):
        rows = report.of(status)
        if not rows:
            continue
        console.print(Text(title, style=style))
        table = Table()
        for col in ("#", "line", "operator", "mutant"):
            table.add_column(col)
        for o in rows:
            why = o.reason if status == EXPLAINED else "" if status == EQUIVALENT else o.detail.splitlines()[0]
            what = o.mutant.description + (f"\n{why}" if why else "")
            table.add_row(str(o.mutant.number), str(o.mutant.line), o.mutant.operator, Text(what))
        console.print(table)
    if report.misleading:
        console.print(Text("misleading declarations (spec_equivalent names a mutant the checks kill):", style="red"))
        for line in report.misleading:
            console.print(Text(f"  {line}"))
    score = report.score
    # one decimal, so that a survivor among hundreds never shows as 100 %
    shown = "n/a (no mutant changes behaviour)" if score is None else f"{100 * score:.1f}".removesuffix(".0") + " %"
    console.print(
        Text.assemble(
            ("mutation score: ", "bold"),
            (shown, "bold green" if score is not None and score >= 0.9 else "bold red"),
            f"  ({report.count(KILLED)} killed, {report.count(SURVIVED)} survived, {report.count(EXPLAINED)} explained,"
            f" {report.count(EQUIVALENT)} equivalent, {report.count(STILLBORN)} do not load)",
        )
    )


__all__ = [
    "Language",
    "LANGUAGES",
    "Outcome",
    "MutationReport",
    "exercise_mutants",
    "declared_equivalents",
    "mutate_exercise",
    "behaviour",
    "edge_memories",
    "print_mutation_report",
    "KILLED",
    "SURVIVED",
    "EXPLAINED",
    "EQUIVALENT",
    "STILLBORN",
]
