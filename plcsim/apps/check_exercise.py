"""``plcsim check-exercise FILE --seeds N``: does an exercise grade its own programs as it says?

What the repository's own tests do for the shipped exercises, for an instructor's course in their CI: the exercise
ships exactly one reference; the reference and every correct alternative pass every check on every seed 1..N; each
wrong solution names the checks that expose its flaw (``fails=``) and fails each of them on every seed. The
programs are the instructor's, so they are graded in this process (no sandbox), scenario by scenario as
``plcsim grade`` does.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass, field

from rich.console import Console
from rich.text import Text

from plcsim.exercise.model import Exercise, Solution
from plcsim.grading.grader import grade


@dataclass
class SolutionCheck:
    """How one shipped program graded on the seeds, and what is wrong with that (``problems``; none: as it says)."""

    solution: str
    kind: str
    seeds: tuple[int, ...]
    problems: list[str] = field(default_factory=list)

    @property
    def ok(self) -> bool:
        return not self.problems


def check_exercise(
    exercise: Exercise, seeds: Sequence[int], progress: Callable[[int, int], None] | None = None
) -> list[SolutionCheck]:
    """Grade every program the exercise ships on every seed; one :class:`SolutionCheck` per program, and one for
    the exercise itself (``solution="(exercise)"``) where its shipped programs lack a reference."""
    out: list[SolutionCheck] = []
    references = [s.name for s in exercise.solutions if s.kind == "reference"]
    if len(references) != 1:
        found = f"{len(references)} ({', '.join(references)})" if references else "none"
        problem = f"an exercise ships exactly one reference solution (kind='reference'); it ships {found}"
        out.append(SolutionCheck("(exercise)", "-", tuple(seeds), [problem]))
    total, done = len(exercise.solutions) * len(seeds), 0
    for solution in exercise.solutions:
        result = SolutionCheck(solution.name, solution.kind, tuple(seeds))
        if solution.kind == "wrong" and not solution.fails:
            result.problems.append("a wrong solution names the checks that expose its flaw: fails=('check name',)")
        for seed in seeds:
            result.problems += _graded(exercise, solution, seed)
            done += 1
            if progress is not None:
                progress(done, total)
        out.append(result)
    return out


def _graded(exercise: Exercise, solution: Solution, seed: int) -> list[str]:
    """What is wrong with ``solution``'s grade on ``seed`` (nothing: it graded as its kind and ``fails=`` say)."""
    report = grade(exercise, solution.path, seed=seed, scenarios=solution.scenarios)
    if report.error is not None:
        return [f"seed {seed}: it did not run: {report.error}"]
    failed = {c.check: c for c in report.failed()}
    if solution.kind != "wrong":
        return [f"seed {seed}: {c.scenario}: {c.check}: {c.status}: {c.message}" for c in report.failed()]
    missing = [name for name in solution.fails if name not in failed]
    if not missing:
        return []
    passed = ", ".join(repr(name) for name in missing)
    really = f"it failed {sorted(failed)}" if failed else "it passed every check"
    return [f"seed {seed}: should fail {passed} ({solution.explanation or 'its flaw'}); {really}"]


def print_exercise_check(exercise: Exercise, results: Sequence[SolutionCheck], console: Console | None = None) -> None:
    """One line per shipped program (✓ it graded as it says, ✗ it did not), the problems below it; every text from
    the exercise or a grade is printed as plain text, never read as markup."""
    console = console or Console()
    seeds = results[0].seeds if results else ()
    console.print(Text(f"exercise {exercise.number} {exercise.title}: its programs on seeds {_seeds(seeds)}"))
    for r in results:
        mark = ("✓", "green") if r.ok else ("✗", "red")
        verdict = "as it says" if r.ok else f"{len(r.problems)} problem(s)"
        console.print(Text.assemble("  ", mark, f" {r.solution} [{r.kind}]: {verdict}"))
        for problem in r.problems:
            console.print(Text(f"      {problem}"), soft_wrap=True)  # one line, whole: a CI log is searched
    bad = sum(not r.ok for r in results)
    summary = "every program grades as the exercise says" if not bad else f"{bad} of {len(results)} do not"
    console.print(Text(summary, style="bold green" if not bad else "bold red"))


def _seeds(seeds: Sequence[int]) -> str:
    return ", ".join(map(str, seeds))
