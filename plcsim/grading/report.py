"""The grade of a submission as data, and its files: JSON, JUnit XML, the gradebook CSV.

A report is built by the grader (:mod:`plcsim.grading.scoring`) from checks it ran itself; nothing in it
comes from a submission except texts (messages, file names, the labels an error echoes), which every
writer here passes through :mod:`plcsim.core.untrusted_text` for its medium: JUnit gets only characters
XML 1.0 allows, with control and format characters as visible escapes; the gradebook gets one line per
cell, escaped, never a formula; JSON gets the text as it is, as valid UTF-8.
"""

from __future__ import annotations

import csv
import json
from collections.abc import Sequence
from dataclasses import asdict, dataclass, field
from pathlib import Path
from typing import Any
from xml.etree import ElementTree as ET

from plcsim.core import version
from plcsim.core.untrusted_text import for_csv, for_json, for_xml, visible
from plcsim.core.untrusted_text import spreadsheet_safe as spreadsheet_safe  # the formula guard, still here

SCHEMA_VERSION = 3
"""Version of the JSON report's layout (2: ``schema_version``, ``plcsim_version`` and ``seed`` at the top;
3: each check's ``status``: passed, failed or not exercised)."""

ERROR_KINDS_OF_THE_GRADER = frozenset({"grader error"})
"""Outcomes that are the grader's or the instructor's fault, never the student's."""


PASSED, FAILED, NOT_EXERCISED = "passed", "failed", "not exercised"
"""The statuses of a check: ``not exercised`` held only because the behaviour it guards never
happened (see :mod:`plcsim.check.exercised`); it earns nothing and is not passed."""


@dataclass
class CheckResult:
    """One check in one scenario; ``status`` is passed, failed or not exercised."""

    scenario: str
    check: str
    passed: bool
    message: str
    points: float
    max_points: float
    at_ns: int | None = None
    signals: list[str] = field(default_factory=list)
    window: tuple[int, int] | None = None
    diagram: str | None = None
    status: str = ""
    ladder: str | None = None
    """The ladder of the networks writing the check's signals at the scan where it failed, if written."""

    def __post_init__(self) -> None:
        if not self.status:
            self.status = PASSED if self.passed else FAILED


@dataclass
class ScenarioRun:
    """How one scenario ran."""

    scenario: str
    seed: int
    simulated_ns: int
    scans: int
    cpu_mode: str
    cpu_error: str | None = None
    rrd: str | None = None
    trace_npz: str | None = None


@dataclass
class Report:
    """The grade of one submission for one exercise."""

    exercise: str
    title: str
    submission: str
    passed: bool = False
    score: float = 0.0
    max_score: float = 0.0
    checks: list[CheckResult] = field(default_factory=list)
    runs: list[ScenarioRun] = field(default_factory=list)
    error: str | None = None
    error_kind: str | None = None
    warnings: list[str] = field(default_factory=list)
    elapsed_s: float = 0.0
    seed: int | None = None

    @property
    def student(self) -> str:
        """The submission's file name without its folder and suffix (a JUnit class name, a file stem)."""
        return Path(self.submission).stem or self.submission

    @property
    def grader_failed(self) -> bool:
        """True if the grade is void because of the grader or the exercise, not the submission."""
        return self.error_kind in ERROR_KINDS_OF_THE_GRADER

    @property
    def file_stem(self) -> str:
        """:attr:`student` as the name of a file or folder the grader writes (see :func:`file_stem`; a
        batch's writers use :func:`file_stems`, distinct within the batch)."""
        return file_stem(self.submission)

    def to_dict(self) -> dict[str, Any]:
        """The report as JSON data: every text as it is, only lone surrogates (a file name of bytes that are
        not UTF-8) escaped, so that the file is valid UTF-8."""
        return {
            "schema_version": SCHEMA_VERSION,
            "plcsim_version": version.__version__,
            "seed": self.seed,
            **_json_texts(asdict(self)),
        }

    @classmethod
    def from_dict(cls, data: dict[str, Any]) -> Report:
        data = {k: v for k, v in data.items() if k not in ("schema_version", "plcsim_version")}
        data["checks"] = [
            CheckResult(**{**c, "window": tuple(c["window"]) if c.get("window") is not None else None})
            for c in data.get("checks", [])
        ]  # JSON has no tuples: a window comes back as a list
        data["runs"] = [ScenarioRun(**r) for r in data.get("runs", [])]
        return cls(**data)

    def to_json(self, path: str | Path | None = None) -> str:
        text = json.dumps(self.to_dict(), indent=2)
        if path is not None:
            Path(path).write_text(text, encoding="utf-8")
        return text

    def failed(self) -> list[CheckResult]:
        """The checks that did not pass: failed or not exercised."""
        return [c for c in self.checks if not c.passed]

    def not_exercised(self) -> list[CheckResult]:
        return [c for c in self.checks if c.status == NOT_EXERCISED]

    def result(self, check: str, scenario: str | None = None) -> CheckResult:
        """The result of one check (in one scenario, or the first failing/any scenario)."""
        found = [c for c in self.checks if c.check == check and (scenario is None or c.scenario == scenario)]
        if not found:
            raise KeyError(f"no result for check {check!r}; checks: {sorted({c.check for c in self.checks})}")
        failing = [c for c in found if not c.passed]
        return failing[0] if failing else found[0]

    def to_junit(self, path: str | Path | None = None) -> str:
        """JUnit XML: one test suite per scenario, one test case per check; a submission that did not
        run, a CPU STOP and a grader error are ``<error>``s, a failed check a ``<failure>``, a check
        that was not exercised ``<skipped>``."""
        return write_junit([self], path, name=f"plcsim {self.exercise}")


def file_stem(submission: str | Path) -> str:
    r"""A submission's file name without its suffix, as the name of a file or folder the grader writes
    (``alice.json``, ``gs/alice/``): control characters escaped, never ``.``, ``..`` or hidden (the file
    ``...py`` has the stem ``..``).

    >>> file_stem("subs/alice.py"), file_stem("...py"), file_stem("a\x1b[2J.py")
    ('alice', '_..', 'a\\x1b[2J')
    """
    return _file_name(Path(submission).stem or "submission")


def _file_name(text: str) -> str:
    name = visible(text, newlines=False)
    return "_" + name if name.startswith(".") else name


def file_stems(submissions: Sequence[str | Path]) -> list[str]:
    """One distinct :func:`file_stem` per submission of a batch, so that no student's files overwrite
    another's: the stem alone where it is unique, the whole file name where two share a stem (``alice.py``
    and ``alice.il`` write ``alice.py.json`` and ``alice.il.json``), compared without case as Windows and
    macOS compare file names; a name still shared gets ``-2``, ``-3`` ... in the batch's order.

    >>> file_stems(["a/alice.py", "b/alice.il", "bob.py", "x/Bob.py", "y/bob.py"])
    ['alice.py', 'alice.il', 'bob.py', 'Bob.py-2', 'bob.py-3']
    """
    stems = [file_stem(s) for s in submissions]
    shared = _shared(stems)
    names = [
        _file_name(Path(s).name) if stem.casefold() in shared else stem
        for s, stem in zip(submissions, stems, strict=True)
    ]
    seen: dict[str, int] = {}
    distinct = []
    for name in names:
        count = seen[name.casefold()] = seen.get(name.casefold(), 0) + 1
        distinct.append(name if count == 1 else f"{name}-{count}")
    return distinct


def _shared(stems: Sequence[str]) -> set[str]:
    counts: dict[str, int] = {}
    for stem in stems:
        counts[stem.casefold()] = counts.get(stem.casefold(), 0) + 1
    return {stem for stem, count in counts.items() if count > 1}


def _json_texts(data: Any) -> Any:
    if isinstance(data, str):
        return for_json(data)
    if isinstance(data, dict):
        return {key: _json_texts(value) for key, value in data.items()}
    if isinstance(data, list | tuple):
        return [_json_texts(value) for value in data]
    return data


# -- Gradescope --------------------------------------------------------------------------------------

GRADESCOPE_VISIBILITY = ("hidden", "after_due_date", "after_published", "visible")
"""The visibility values Gradescope's autograder results (``results.json``) accept."""


def gradescope_results(report: Report, *, visibility: str = "visible") -> dict[str, Any]:
    """Gradescope's ``results.json`` of a report: the score, one test per scenario and check (its
    score, max_score, status passed/failed and the reason as output), and, when the submission did not
    run, one test saying why. A not-exercised check is a failed test tagged ``not exercised``. The
    maximum and plcsim's version go into ``extra_data`` (Gradescope takes the maximum from the tests)."""
    if visibility not in GRADESCOPE_VISIBILITY:
        raise ValueError(f"Gradescope visibility is one of {', '.join(GRADESCOPE_VISIBILITY)}, not {visibility!r}")
    tests = [
        {
            "name": _shown(f"{c.scenario}: {c.check}"),
            "score": c.points,
            "max_score": c.max_points,
            "status": PASSED if c.passed else FAILED,
            "output": _shown(c.message + (f"\ntiming diagram: {c.diagram}" if c.diagram else "")),
            "tags": [c.status] if c.status == NOT_EXERCISED else [],
            "visibility": visibility,
        }
        for c in report.checks
    ]
    if report.error:
        blame = " (a fault of the grader or the exercise, not of the submission)" if report.grader_failed else ""
        tests.append(
            {
                "name": _shown(report.error_kind or "error"),
                "score": 0.0,
                "max_score": 0.0 if report.checks else report.max_score,
                "status": FAILED,
                "output": _shown(report.error + blame),
                "visibility": visibility,
            }
        )
    verdict = "PASSED" if report.passed else "FAILED"

    return {
        "score": report.score,
        "execution_time": round(report.elapsed_s, 3),
        "output": _shown(
            f"{report.exercise} {report.title}: {verdict}, {report.score:g} / {report.max_score:g} points"
            + "".join(f"\nwarning: {w}" for w in report.warnings)
        ),
        "visibility": visibility,
        "stdout_visibility": "hidden",
        "output_format": "text",  # shown as text, never as Markdown or HTML: a message may quote the program
        "test_output_format": "text",
        "test_name_format": "text",
        "tests": tests,
        "extra_data": {
            "max_score": report.max_score,
            "exercise": report.exercise,
            "seed": report.seed,
            "error_kind": report.error_kind and _shown(report.error_kind),
            "plcsim_version": version.__version__,
        },
    }


_shown = for_xml
"""Gradescope shows each output as text on a web page: the escapes and the cut of a JUnit text."""


def write_gradescope(report: Report, path: str | Path, *, visibility: str = "visible") -> Path:
    """Write :func:`gradescope_results` to ``path`` (``/autograder/results/results.json`` on Gradescope)."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(json.dumps(gradescope_results(report, visibility=visibility), indent=2), encoding="utf-8")
    return path


# -- JUnit ------------------------------------------------------------------------------------------


def write_junit(reports: Sequence[Report], path: str | Path | None = None, *, name: str | None = None) -> str:
    """JUnit XML of one or many reports (a batch); written to ``path`` if given."""
    suites = [s for r in reports for s in _suites(r)]
    root = ET.Element("testsuites", name=for_xml(name or f"plcsim {reports[0].exercise if reports else ''}".strip()))
    root.extend(suites)
    _count(root, suites, sum(r.elapsed_s for r in reports))
    text = ET.tostring(root, encoding="unicode")
    if path is not None:
        Path(path).write_text('<?xml version="1.0" encoding="utf-8"?>\n' + text, encoding="utf-8")
    return text


def _suites(report: Report) -> list[ET.Element]:
    """The suites of one report; every text goes through :func:`for_xml` (XML 1.0's characters only)."""
    suites: list[ET.Element] = []
    per_run = report.elapsed_s / max(1, len(report.runs))
    if report.error and not report.checks:
        suite = ET.Element("testsuite", name=for_xml(report.exercise))
        case = _case(suite, "load", f"{report.student}.{report.exercise}", report.elapsed_s)
        _error(case, report.error_kind or "error", report.error)
        suites.append(suite)
    by_scenario: dict[str, list[CheckResult]] = {}
    for c in report.checks:
        by_scenario.setdefault(c.scenario, []).append(c)
    stopped = {run.scenario: run.cpu_error for run in report.runs if run.cpu_error}
    for scenario, results in by_scenario.items():
        suite = ET.Element("testsuite", name=for_xml(f"{report.exercise}.{scenario}"))
        classname = f"{report.student}.{report.exercise}.{scenario}"
        if scenario in stopped:
            _error(_case(suite, "CPU run", classname, 0.0), "CPU STOP", stopped[scenario])
        for r in results:
            case = _case(suite, r.check, classname, per_run / max(1, len(results)) if scenario != "static" else 0.0)
            message = for_xml(r.message)
            if r.status == NOT_EXERCISED:
                ET.SubElement(case, "skipped", message=message).text = message
            elif not r.passed:
                failure = ET.SubElement(case, "failure", message=message, type="check failed")
                failure.text = for_xml(r.message + (f"\ntiming diagram: {r.diagram}" if r.diagram else ""))
        suites.append(suite)
    if report.error and report.checks:  # a grader error after the checks ran
        suite = ET.Element("testsuite", name=for_xml(f"{report.exercise}.grader"))
        case = _case(suite, "grading", f"{report.student}.{report.exercise}", 0.0)
        _error(case, report.error_kind or "error", report.error)
        suites.append(suite)
    for suite in suites:
        cases = suite.findall("testcase")
        _count(suite, cases, sum(float(c.get("time", "0")) for c in cases))
    return suites


def _case(suite: ET.Element, name: str, classname: str, seconds: float) -> ET.Element:
    return ET.SubElement(suite, "testcase", name=for_xml(name), classname=for_xml(classname), time=f"{seconds:.3f}")


def _error(case: ET.Element, kind: str, message: str) -> None:
    shown = for_xml(message)
    ET.SubElement(case, "error", message=shown, type=for_xml(kind)).text = shown


_COUNTED = {"failures": "failure", "errors": "error", "skipped": "skipped"}
"""The count attributes of a suite and the element of a test case each counts."""


def _count(element: ET.Element, children: Sequence[ET.Element], seconds: float) -> None:
    """Set tests/failures/errors/skipped/time of a suite (children: test cases) or of the root (children:
    suites). A check that was not exercised is ``skipped``: it did not run as a test of the behaviour."""
    suite = element.tag == "testsuite"
    element.set("tests", str(len(children) if suite else sum(int(s.get("tests", "0")) for s in children)))
    for key, tag in _COUNTED.items():
        if suite:
            number = sum(c.find(tag) is not None for c in children)
        else:
            number = sum(int(s.get(key, "0")) for s in children)
        element.set(key, str(number))
    element.set("time", f"{seconds:.3f}")


# -- gradebook ----------------------------------------------------------------------------------------

_CELL = {PASSED: "pass", FAILED: "FAIL", NOT_EXERCISED: "not exercised"}


def one_line(text: str, limit: int = 200) -> str:
    """The first line of a message, cut to ``limit`` characters, control characters shown as escapes.

    Kept for plcsim 0.1's callers (``plcsim.grade_report.one_line``; the reports themselves use
    :mod:`plcsim.core.untrusted_text`); it goes with :mod:`plcsim.core.moved` in the next release.

    >>> one_line("alice.py, line 2: syntax error\\n    t.LED = (\\n          ^")
    'alice.py, line 2: syntax error …'
    """
    lines = text.strip().splitlines() or [""]
    first = lines[0].strip()
    cut = len(first) > limit or len(lines) > 1
    return visible(first[:limit], newlines=False) + (" …" if cut else "")


def cpu_state(report: Report) -> str:
    """The CPU's state over the scenarios: ``RUN``, ``STOP in <scenario>: <why>``, or ``-`` (it did not run)."""
    if not report.runs:
        return "-"
    stopped = [run for run in report.runs if run.cpu_mode != "RUN" or run.cpu_error]
    if not stopped:
        return "RUN"
    first = stopped[0]
    more = f" (and {len(stopped) - 1} more)" if len(stopped) > 1 else ""
    return f"{first.cpu_mode} in {first.scenario}{more}: {first.cpu_error or 'no reason given'}"


def write_gradebook(reports: Sequence[Report], path: str | Path) -> Path:
    """A CSV with one row per submission: score, max, passed, the error (its kind and first line), the
    CPU's state, and each check's result (pass, FAIL, not exercised, or - where it did not run)."""
    checks: list[str] = []
    for r in reports:
        for c in r.checks:
            key = f"{c.scenario}: {c.check}"
            if key not in checks:
                checks.append(key)
    path = Path(path)
    with path.open("w", newline="", encoding="utf-8") as f:
        writer = csv.writer(f)
        header = ["submission", "score", "max_score", "percent", "passed", "error", "cpu", *checks]
        writer.writerow([for_csv(h) for h in header])
        for r in reports:
            results = {f"{c.scenario}: {c.check}": _CELL[c.status] for c in r.checks}
            percent = f"{100 * r.score / r.max_score:.1f}" if r.max_score else "0.0"
            error = f"{r.error_kind or 'error'}: {r.error}" if r.error else ""
            row = [
                for_csv(Path(r.submission).name),
                f"{r.score:g}",
                f"{r.max_score:g}",
                percent,
                "yes" if r.passed else "no",
                for_csv(error),
                for_csv(cpu_state(r)),
                *(results.get(c, "-") for c in checks),
            ]
            writer.writerow(row)
    return path
