"""pytest plugin for instructors: run and grade PLC programs from ordinary pytest tests.

Installed with plcsim (entry point ``pytest11``: ``plcsim``); nothing to import. In a test file::

    from plcsim.check import all_of, never, rises

    def test_the_belt_stops_at_s2(plcsim_run):
        run = plcsim_run("4.3.6", program="submissions/alice.py", scenario="five objects", seed=1)
        run.require(never(all_of("D1", "S2")))      # fails with the check's own explanation
        assert len(run.trace.rises("D1")) == 5       # or read the trace directly

    def test_the_whole_exercise(plcsim_grade):
        report = plcsim_grade("4.3.6")               # the program given by --plcsim-program
        assert report.passed, [c.message for c in report.failed()]

Fixtures:

* ``plcsim_run(exercise, program=None, *, scenario=None, seed=None, solution=None, sandbox=None,
  limits=None)`` runs one scenario and returns a :class:`PlcRun` (trace, CPU state, ``check()`` and
  ``require()`` for the checker language of :mod:`plcsim.check`);
* ``plcsim_grade(exercise, program=None, *, seed=None, scenarios=None, solution=None, sandbox=None,
  limits=None)`` grades every scenario and check and returns the :class:`~plcsim.grading.report.Report`;
* ``plcsim_program``: the submission of ``--plcsim-program`` (None without it);
  ``plcsim_seed``: the seed (1, or each of ``--plcsim-seeds``).

``exercise`` is a textbook number (``4.3.6``), a slug or an instructor's exercise file. A program is
graded as untrusted: in the sandbox's confined child (:mod:`plcsim.grading.sandbox.parent`), unless the instructor
opts out with ``sandbox=False`` or ``--plcsim-no-sandbox`` (trusted programs only: it runs in the
test process). Results are cached for the session, so many tests of one submission run it once.

Options:

* ``--plcsim-program PATH``: the submission the tests without ``program=`` run; a folder of ``.py``
  files runs every such test once per file (the student's name in the test id);
* ``--plcsim-seeds 1,2,3``: run every such test once per seed (default: seed 1);
* ``--plcsim-exercise 4.3.6`` (repeatable): add one test item per scenario and check of the exercise,
  for each program of ``--plcsim-program`` and seed: pytest reports every check of the grade;
* ``--plcsim-no-sandbox``: run programs in the test process (trusted programs only).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import pytest

from plcsim.core.untrusted_text import for_terminal

__all__ = ["PlcRun", "SubmissionError"]


class SubmissionError(AssertionError):
    """The program could not be run to the end of a scenario: not loadable, or stopped at a limit."""


@dataclass
class PlcRun:
    """One scenario of a program: the trace and how the CPU ended, with the checker language at hand."""

    exercise: Any
    scenario: str
    seed: int
    program: Path
    trace: Any
    cpu_mode: str
    cpu_error: str | None
    simulated_ns: int
    scans: int
    warnings: list[str] = field(default_factory=list)
    analysis: Any = None
    sandboxed: bool = True
    """False if the program ran in the test process (``sandbox=False``, ``--plcsim-no-sandbox``)."""

    @property
    def stopped(self) -> bool:
        """True if the CPU went to STOP (a program error, the cycle watchdog)."""
        return self.cpu_mode == "STOP"

    def check(self, check: Any) -> Any:
        """Evaluate a check of :mod:`plcsim.check` on this run: its :class:`~plcsim.check.Verdict`."""
        from plcsim.check.base import Context

        return check.evaluate(Context.of(self.trace, self.analysis))

    def require(self, *checks: Any) -> None:
        """Assert that every check holds; a failure says what was expected, what happened and when."""
        failed = [(c, v) for c in checks for v in [self.check(c)] if not v.passed]
        if failed:
            lines = [f"{c.title}: {v.message}" for c, v in failed]
            if self.cpu_error:
                lines.append(f"(the CPU stopped: {self.cpu_error})")
            said = f"{self.program.name}, scenario {self.scenario!r}, seed {self.seed}:\n  " + "\n  ".join(lines)
            raise AssertionError(for_terminal(said, newlines=True))


# -- options and fixtures -----------------------------------------------------------------------------------


def pytest_addoption(parser: pytest.Parser) -> None:
    group = parser.getgroup("plcsim", "plcsim: running and grading PLC programs")
    group.addoption(
        "--plcsim-program",
        metavar="PATH",
        help="the submission tests run when they name no program= (a folder: each .py file in turn)",
    )
    group.addoption("--plcsim-seeds", metavar="1,2,3", help="run the plcsim tests once per seed (default 1)")
    group.addoption(
        "--plcsim-exercise",
        action="append",
        default=[],
        metavar="EXERCISE",
        help="add a test item per scenario and check of EXERCISE for the --plcsim-program submission(s)",
    )
    group.addoption(
        "--plcsim-no-sandbox",
        action="store_true",
        help="run programs in the test process instead of the sandbox (trusted programs only)",
    )


def _programs(config: pytest.Config) -> list[Path]:
    option = config.getoption("plcsim_program")
    if not option:
        return []
    path = Path(option)
    if path.is_dir():
        files = sorted(p for p in path.glob("*.py") if p.is_file() and not _is_test_file(p))
        if not files:
            raise pytest.UsageError(f"--plcsim-program {option}: no .py files in this folder")
        return files
    if not path.is_file():
        raise pytest.UsageError(f"--plcsim-program {option}: no such file or folder")
    return [path]


def _is_test_file(path: Path) -> bool:
    """A pytest file beside the submissions (``test_*.py``, ``*_test.py``, ``conftest.py``) is not one."""
    return path.name == "conftest.py" or path.name.startswith("test_") or path.stem.endswith("_test")


def _seeds(config: pytest.Config) -> list[int]:
    option = config.getoption("plcsim_seeds")
    if not option:
        return [1]
    try:
        seeds = [int(s) for s in option.split(",") if s.strip()]
    except ValueError:
        raise pytest.UsageError(f"--plcsim-seeds {option!r}: give whole numbers separated by commas (1,2,3)") from None
    if not seeds:
        raise pytest.UsageError("--plcsim-seeds: give at least one seed (1,2,3)")
    return seeds


def pytest_generate_tests(metafunc: pytest.Metafunc) -> None:
    """One test per program of a ``--plcsim-program`` folder and per seed of ``--plcsim-seeds``."""
    config = metafunc.config
    if "plcsim_program" in metafunc.fixturenames and config.getoption("plcsim_program"):
        programs = _programs(config)
        metafunc.parametrize("plcsim_program", programs, ids=[p.stem for p in programs], indirect=True)
    if "plcsim_seed" in metafunc.fixturenames and config.getoption("plcsim_seeds"):
        seeds = _seeds(config)
        metafunc.parametrize("plcsim_seed", seeds, ids=[f"seed{s}" for s in seeds], indirect=True)


@pytest.fixture
def plcsim_program(request: pytest.FixtureRequest) -> Path | None:
    """The submission of ``--plcsim-program`` (one file of it, for a folder), or None."""
    return getattr(request, "param", None)


@pytest.fixture
def plcsim_seed(request: pytest.FixtureRequest) -> int:
    """The seed of this test: 1, or one of ``--plcsim-seeds``."""
    return getattr(request, "param", 1)


@pytest.fixture
def plcsim_run(request: pytest.FixtureRequest, plcsim_program: Path | None, plcsim_seed: int) -> Any:
    """``plcsim_run(exercise, program=None, *, scenario=None, seed=None, ...)``: run one scenario (see the module)."""
    runner = _Runner(request.config, plcsim_program, plcsim_seed)
    return runner.run


@pytest.fixture
def plcsim_grade(request: pytest.FixtureRequest, plcsim_program: Path | None, plcsim_seed: int) -> Any:
    """``plcsim_grade(exercise, program=None, *, seed=None, ...)``: grade every scenario (see the module)."""
    runner = _Runner(request.config, plcsim_program, plcsim_seed)
    return runner.grade


_CACHE = pytest.StashKey[dict]()


class _Runner:
    """Resolves the exercise, the program, the seed and the sandbox of a call; caches results per session."""

    def __init__(self, config: pytest.Config, program: Path | None, seed: int) -> None:
        self.config = config
        self.default_program = program
        self.default_seed = seed
        self.cache: dict[tuple[Any, ...], Any] = config.stash.setdefault(_CACHE, {})

    def _resolve(
        self, exercise: Any, program: str | Path | None, solution: str | None, seed: int | None, sandbox: bool | None
    ) -> tuple[Any, Path, int, bool]:
        ex = _exercise(exercise)
        if program is not None and solution is not None:
            raise pytest.UsageError("plcsim: give program= or solution=, not both")
        if solution is not None:
            path = ex.solution(solution).path
        elif program is not None:
            path = Path(program)
        elif self.default_program is not None:
            path = self.default_program
        else:
            raise pytest.UsageError(
                "plcsim: which program? pass program='FILE.py' (or solution='reference') or run pytest "
                "with --plcsim-program FILE.py"
            )
        confined = not self.config.getoption("plcsim_no_sandbox") if sandbox is None else sandbox
        return ex, Path(path).resolve(), self.default_seed if seed is None else seed, confined

    def run(
        self,
        exercise: Any,
        program: str | Path | None = None,
        *,
        scenario: str | None = None,
        seed: int | None = None,
        solution: str | None = None,
        sandbox: bool | None = None,
        limits: Any = None,
    ) -> PlcRun:
        ex, path, seed, confined = self._resolve(exercise, program, solution, seed, sandbox)
        name = ex.scenario(scenario).name if scenario else ex.scenarios[0].name
        key = ("run", ex.number, ex.slug, path, name, seed, confined, _limits_key(limits))
        if key not in self.cache:
            self.cache[key] = _run_one(ex, path, name, seed, confined, limits)
        found = self.cache[key]
        if isinstance(found, SubmissionError):
            raise found
        return found

    def grade(
        self,
        exercise: Any,
        program: str | Path | None = None,
        *,
        seed: int | None = None,
        scenarios: list[str] | None = None,
        solution: str | None = None,
        sandbox: bool | None = None,
        limits: Any = None,
    ) -> Any:
        from plcsim.grading.grader import grade, grade_sandboxed

        ex, path, seed, confined = self._resolve(exercise, program, solution, seed, sandbox)
        key = ("grade", ex.number, ex.slug, path, seed, confined, tuple(scenarios or ()), _limits_key(limits))
        if key not in self.cache:
            if confined:
                self.cache[key] = grade_sandboxed(ex, path, seed=seed, scenarios=scenarios, limits=limits)
            else:
                self.cache[key] = grade(ex, path, seed=seed, scenarios=scenarios)
        return self.cache[key]


def _limits_key(limits: Any) -> tuple[Any, ...] | None:
    """The sandbox limits as part of a cache key (Limits is not hashable)."""
    return None if limits is None else (limits.cpu_seconds, limits.memory_mb, limits.wall_seconds)


def _exercise(exercise: Any) -> Any:
    """An exercise by number, slug or file (an Exercise is taken as it is)."""
    from plcsim.core.errors import PlcError
    from plcsim.exercise.model import Exercise

    if isinstance(exercise, Exercise):
        return exercise
    from plcsim.exercise.catalog import get

    try:
        return get(str(exercise))
    except PlcError as exc:
        raise pytest.UsageError(f"plcsim: {exc}") from None


def _run_one(ex: Any, path: Path, scenario: str, seed: int, confined: bool, limits: Any) -> PlcRun | SubmissionError:
    from plcsim.core.errors import PlcError
    from plcsim.grading.grader import parent_analysis
    from plcsim.grading.run import load_error_kind, run_scenarios
    from plcsim.grading.sandbox.limits import Limits

    try:
        analysis = parent_analysis(ex, path)
        if confined:
            from plcsim.grading.sandbox.parent import run_child

            outcome = run_child(ex, path, seed, [ex.scenario(scenario)], limits or Limits())
            if outcome.kind is not None:
                return SubmissionError(
                    for_terminal(f"{path.name} did not run ({outcome.kind}): {outcome.message}", newlines=True)
                )
            (result,) = outcome.runs
            notes = list(outcome.notes)
        else:
            from plcsim.frontends import read_program

            (result,), _ = run_scenarios(ex, read_program(path), seed=seed, scenarios=[scenario])
            notes = []
    except PlcError as exc:
        return SubmissionError(for_terminal(f"{path.name} did not run ({load_error_kind(exc)}): {exc}", newlines=True))
    return PlcRun(
        ex,
        result.scenario,
        seed,
        path,
        result.trace,
        result.cpu_mode,
        result.cpu_error or result.plant_error,
        result.simulated_ns,
        result.scans,
        notes + list(result.warnings),
        analysis,
        confined,
    )


# -- an exercise's checks as test items -----------------------------------------------------------------------


def pytest_collection_modifyitems(session: pytest.Session, config: pytest.Config, items: list[pytest.Item]) -> None:
    """``--plcsim-exercise``: one item per scenario and check, for every program and seed asked for."""
    wanted = config.getoption("plcsim_exercise")
    if not wanted:
        return
    programs = _programs(config)
    if not programs:
        raise pytest.UsageError("--plcsim-exercise needs the submission(s) to grade: --plcsim-program PATH")
    for name in wanted:
        exercise = _exercise(name)
        for program in programs:
            for seed in _seeds(config):
                label = f"plcsim {exercise.number} {for_terminal(program.stem)} seed {seed}"
                items.extend(
                    ExerciseGrade.from_parent(
                        session, name=label, exercise=exercise, program=program, seed=seed
                    ).collect()
                )


class ExerciseGrade(pytest.Collector):
    """The grade of one program on one exercise and seed, as one item per scenario and check."""

    def __init__(self, *, exercise: Any, program: Path, seed: int, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        self.exercise, self.program, self.seed = exercise, program, seed

    def collect(self) -> list[pytest.Item]:
        from plcsim.check import StaticCheck

        items: list[pytest.Item] = []
        static_done = set()
        for scenario in self.exercise.scenarios:
            for gc in self.exercise.checks_for(scenario.name):
                static = isinstance(gc.check, StaticCheck)
                if static and gc.name in static_done:
                    continue
                static_done.add(gc.name)
                where = "static" if static else scenario.name
                items.append(CheckItem.from_parent(self, name=f"{where}: {gc.name}", scenario=where, check=gc.name))
        return items

    def report(self) -> Any:
        runner = _Runner(self.config, self.program, self.seed)
        return runner.grade(self.exercise)


class CheckError(AssertionError):
    """A check of the grade did not pass (failed, not exercised, or the submission did not run)."""


class CheckItem(pytest.Item):
    """One check in one scenario of an exercise's grade."""

    def __init__(self, *, scenario: str, check: str, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        self.scenario, self.check = scenario, check

    def runtest(self) -> None:
        report = self.parent.report()  # type: ignore[union-attr]
        if report.error is not None:
            said = f"{report.submission} did not run ({report.error_kind}): {report.error}"
            raise CheckError(for_terminal(said, newlines=True))
        result = report.result(self.check, self.scenario)
        if not result.passed:
            raise CheckError(for_terminal(f"{result.status}: {result.message}", newlines=True))

    def repr_failure(self, excinfo: pytest.ExceptionInfo[BaseException], style: Any = None) -> str:
        if isinstance(excinfo.value, CheckError):
            return str(excinfo.value)
        return super().repr_failure(excinfo)

    def reportinfo(self) -> tuple[Path, int | None, str]:
        grade = self.parent
        return grade.program, None, f"{grade.name} :: {self.name}"  # type: ignore[union-attr]
