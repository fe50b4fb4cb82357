"""Grade a batch of submissions: each in its own confined child, through an executor (threads, Dask).

A batch ships one :class:`GradingTask` per submission to wherever the executor runs it
(:mod:`plcsim.grading.executors`); the task grades it with
:func:`~plcsim.grading.grader.grade_sandboxed`. The exercise goes along as itself (threads of this
process) or as an :class:`ExerciseRef` another process imports. The trusted probe runs once for the
whole batch (:class:`~plcsim.grading.sandbox.probes.Probes`), and a task that fails is a grader error
of that submission alone.
"""

from __future__ import annotations

import contextlib
import importlib
import sys
from collections.abc import Callable, Iterable
from concurrent.futures import Executor, Future, ThreadPoolExecutor, as_completed
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from plcsim.core import version
from plcsim.core.errors import ConfigurationError
from plcsim.exercise.model import Exercise
from plcsim.grading.budget import fitted_limits
from plcsim.grading.grader import grade_sandboxed
from plcsim.grading.report import Report, file_stems
from plcsim.grading.run import chosen_scenarios
from plcsim.grading.sandbox.limits import Limits
from plcsim.grading.scoring import failure_report

EXPORT_DIRS = ("rrd_dir", "plots_dir", "traces_dir")
"""The options of :func:`grade` naming folders the grader writes files into."""


def per_student(folder: str | Path | None, stem: str) -> Path | None:
    """A student's own folder below ``folder``, named by the submission's distinct stem in the batch (its
    file name without ``.py``; never outside ``folder``: see :func:`~plcsim.grading.report.file_stems`)."""
    return None if folder is None else Path(folder) / stem


@dataclass(frozen=True)
class ExerciseRef:
    """How a grading process elsewhere imports the exercise: its module and attribute, and the folder
    to put on ``sys.path`` first for an instructor's exercise file found by path."""

    module: str
    attribute: str
    root: str | None = None

    @classmethod
    def of(cls, exercise: Exercise) -> ExerciseRef:
        """Raises ConfigurationError for an exercise no module defines (one built in a test or notebook)."""
        from plcsim.grading.sandbox.importable import locate, package_root

        module, attribute = locate(exercise)
        top = package_root(sys.modules[module])
        return cls(module, attribute, str(top.parent) if top is not None else None)

    def resolve(self) -> Exercise:
        if self.root is not None and self.module not in sys.modules and self.root not in sys.path:
            sys.path.append(self.root)  # last, like exercises.load_path: it never shadows an installed module
        exercise = getattr(importlib.import_module(self.module), self.attribute)
        if not isinstance(exercise, Exercise):
            raise ConfigurationError(f"{self.module}.{self.attribute} is not an Exercise here")
        return exercise


@dataclass(frozen=True)
class GradingTask:
    """One submission of a batch, as an executor ships it to the process that grades it."""

    exercise: Exercise | ExerciseRef
    """The exercise itself (threads of this process) or how to import it (another process)."""
    path: str
    seed: int
    limits: Limits | None
    probes: Any
    """The batch's :class:`plcsim.grading.sandbox.probes.Probes`, or None to probe in the task."""
    options: dict[str, Any]
    version: str


def grade_task(task: GradingTask) -> Report:
    """Grade one submission of a batch, wherever an executor runs this: the submission in its own
    confined child, the checks here. Whatever this raises becomes a grader error in :func:`grade_batch`."""

    if task.version != version.__version__:
        raise ConfigurationError(
            f"this grading worker runs plcsim {version.__version__}, the grader {task.version}: "
            f"install the same plcsim on every worker"
        )
    exercise = task.exercise.resolve() if isinstance(task.exercise, ExerciseRef) else task.exercise
    return grade_sandboxed(exercise, task.path, seed=task.seed, limits=task.limits, probes=task.probes, **task.options)


def grade_batch(
    exercise: Exercise,
    paths: Iterable[str | Path],
    *,
    jobs: int = 1,
    executor: str | Executor = "local",
    seed: int = 1,
    limits: Limits | None = None,
    progress: Callable[[int, int, Report], None] | None = None,
    budget: bool = True,
    **options: Any,
) -> list[Report]:
    """Grade many submissions, each in its own confined child process, through ``executor``.

    ``executor`` is ``"local"`` (``jobs`` threads here), ``"dask"`` (a Dask cluster of ``jobs`` worker
    processes on this machine), an existing Dask scheduler's address (``"tcp://host:8786"``), see
    :mod:`plcsim.grading.executors`, or any ``concurrent.futures.Executor`` (left open). The reports come in
    the order of ``paths``, whatever order they finish in; a task that fails (its worker died, the
    cluster is gone) is a grader error of that submission alone. ``progress(done, total, report)`` is
    called as each finishes. The trusted probe runs once per scenario for the whole batch.

    Recordings, traces and diagrams (``rrd_dir``, ``traces_dir``, ``plots_dir``) go into one folder per
    student below the folder given (``out/alice/led-1-alice-presses.rrd``).

    ``budget``: stop each submission at the exercise's CPU budget, fitted to its reference's cost
    (measured once here, :mod:`plcsim.grading.budget`): one over it is ``too slow``, not a time limit."""
    from plcsim.grading.executors import open_executor
    from plcsim.grading.sandbox.probes import Probes

    paths = [Path(p) for p in paths]
    stems = file_stems(paths)
    reports: list[Report | None] = [None] * len(paths)
    try:
        probes = Probes.of(exercise, chosen_scenarios(exercise, options.get("scenarios")), seed)
    except Exception:  # noqa: BLE001 - the exercise's mistake: each task probes again and reports it
        probes = None
    if budget:
        chosen = options.get("scenarios")
        limits = fitted_limits(exercise, limits or Limits(), seed=seed, scenarios=chosen)
    opened = open_executor(executor, jobs=jobs) if isinstance(executor, str) else contextlib.nullcontext(executor)
    with opened as pool:
        target = exercise if isinstance(pool, ThreadPoolExecutor) else ExerciseRef.of(exercise)
        futures: dict[Future[Report], int] = {}
        for k, (path, stem) in enumerate(zip(paths, stems, strict=True)):
            mine = {key: per_student(value, stem) if key in EXPORT_DIRS else value for key, value in options.items()}
            task = GradingTask(target, str(path), seed, limits, probes, mine, version.__version__)
            futures[pool.submit(grade_task, task)] = k
        for done, future in enumerate(as_completed(futures), start=1):
            k = futures[future]
            reports[k] = _task_report(future, exercise, paths[k], seed)
            if progress is not None:
                progress(done, len(paths), reports[k])
    return [r for r in reports if r is not None]


def _task_report(future: Future[Report], exercise: Exercise, path: Path, seed: int) -> Report:
    """The task's report, or, if the task itself failed, a grader error of this submission alone."""
    try:
        report = future.result()
    except Exception as exc:  # noqa: BLE001 - a dead worker, a lost cluster, our own bug: never the student's
        message = (
            f"the grading task failed ({type(exc).__name__}: {exc}); the submission was not graded "
            f"(a fault of the grader or its workers, not of the submission)"
        )
        blank = Report(exercise.number, exercise.title, str(path), seed=seed)
        return failure_report(blank, "grader error", message, exercise)
    return report
