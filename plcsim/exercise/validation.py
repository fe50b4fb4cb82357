"""Checking an exercise when it is loaded: every name its scenarios and checks use exists.

An instructor's typo (a station, signal, tag or plant event the exercise does not have, a scenario
``only(...)`` names but nobody wrote) is found here, once, when the exercise module is imported, and
reported with the file and line that made it and the nearest valid names. Left to the run, it would
fail every student's grade instead of the exercise. Every mistake found is reported, not only the
first, in one :class:`~plcsim.core.errors.ExerciseError`.

What a check may read is what the grader's trace always holds: the exercise's tags and the scalar
members of its data blocks (``plcsim.sim.recorder.default_signals`` of a CPU without a program). Names a
student's program declares are not there, since a check cannot rely on them.
"""

from __future__ import annotations

import dataclasses
import re
from collections.abc import Iterable, Iterator
from typing import TYPE_CHECKING, Any

from plcsim.check import Check, Quantity, Span
from plcsim.controllers.choice import controller_for
from plcsim.controllers.protocol import Controller
from plcsim.controllers.s7.config import CPUConfig
from plcsim.core.errors import ExerciseError, PlcError, did_you_mean
from plcsim.core.literals import to_ns
from plcsim.plant.protocol import rig_verbs, stations_of, traced_observables
from plcsim.scenario.names import name_problems, plant_vocabulary
from plcsim.scenario.planning import FAULTS, Scenario
from plcsim.scenario.verbs import VERBS
from plcsim.sim.recorder import default_signals
from plcsim.sim.wiring import Wiring

if TYPE_CHECKING:
    from plcsim.exercise.model import Exercise, GradedCheck

_TASK = re.compile(r"OB\d+", re.IGNORECASE)


def validate(exercise: Exercise) -> None:
    """Raise :class:`ExerciseError` listing every mistake in the exercise's definition (none: return)."""
    problems = _Validation(exercise).problems
    if not problems:
        return
    where = exercise.defined_at
    if len(problems) == 1:
        raise ExerciseError(problems[0], problems)
    listed = "\n  ".join(problems)
    raise ExerciseError(f"{where}: exercise {exercise.number} has {len(problems)} mistakes:\n  {listed}", problems)


def _choices(valid: Iterable[str]) -> str:
    names = list(valid)
    return ", ".join(names) if names else "none"


class _Validation:
    """One pass over an exercise: its rig, tags and wiring first, then scenarios and checks."""

    def __init__(self, exercise: Exercise):
        self.exercise = exercise
        self.problems: list[str] = []
        self.plant: Any = None
        self.cpu: Controller | None = None
        self.wired: list[str] = []
        self._world()
        self._options()
        names = [s.name for s in exercise.scenarios]
        for dup in sorted({n for n in names if names.count(n) > 1}):
            self.add(exercise.defined_at, f"two scenarios are named {dup!r}; give each a name of its own")
        if self.cpu is None:
            return  # without a tag table nothing else can be checked
        for scenario in exercise.scenarios:
            self._scenario(scenario)
        self._checks()
        self._hmi()

    def add(self, where: str, detail: str) -> None:
        """Record one mistake, at the line that made it (and the exercise's own, if that is elsewhere)."""
        home = self.exercise.defined_at
        origin = "" if where.rpartition(":")[0] == home.rpartition(":")[0] else f" (defined at {home})"
        self.problems.append(f"{where}: exercise {self.exercise.number}{origin}: {detail}")

    # -- the rig, the tags, the wiring ----------------------------------------------------------

    def _world(self) -> None:
        ex, home = self.exercise, self.exercise.defined_at
        try:
            self.plant = ex.rig() if ex.rig is not None else None
        except Exception as exc:  # noqa: BLE001 - whatever the rig raises is the exercise's mistake
            self.add(home, f"the rig could not be built: {type(exc).__name__}: {exc}")
            return
        declarations = ("EVENTS", "CAPABILITIES", "VERBS", "event_subjects")
        undeclared = [m for m in declarations if self.plant is not None and not hasattr(self.plant, m)]
        if undeclared:
            self.add(home, f"the rig {self.plant!r} does not declare {undeclared} (see plcsim.plant.protocol.Plant)")
            self.plant = None
            return
        try:
            self.cpu = controller_for(None, ex.tag_table(), **ex.cpu)
        except (PlcError, TypeError) as exc:
            self.add(home, f"the I/O table, data blocks or CPU options are wrong: {exc}")
            return
        if self.plant is not None:
            try:
                self.wired = list(Wiring(self.plant, self.cpu.table, ex.wires()).by_tag)
            except PlcError as exc:
                self.add(home, str(exc))

    def _options(self) -> None:
        ex, home = self.exercise, self.exercise.defined_at
        try:
            if to_ns(ex.dt, "dt") <= 0:
                self.add(home, f"dt={ex.dt!r} must be a positive step such as '1ms'")
        except PlcError as exc:
            self.add(home, f"dt: {exc}")
        names = [s.name for s in ex.scenarios]
        for scenario, options in ex.scenario_cpu.items():
            if scenario not in names:
                self.add(
                    home,
                    f"scenario_cpu names scenario {scenario!r}{did_you_mean(scenario, names)}; "
                    f"scenarios: {_choices(names)}",
                )
                continue
            try:
                CPUConfig(**{**ex.cpu, **options})
            except (PlcError, TypeError) as exc:
                self.add(home, f"scenario_cpu[{scenario!r}]: {exc}")

    @property
    def plant_events(self) -> list[str]:
        """The events the plant can emit (no plant: none)."""
        return [] if self.plant is None else sorted(self.plant.EVENTS)

    @property
    def plant_subjects(self) -> list[str] | None:
        """The names the plant's events are about, a part's id aside (no plant: not checked)."""
        return None if self.plant is None else sorted(self.plant.event_subjects())

    @property
    def plant_verbs(self) -> list[str]:
        """The scenario verbs the rig brings."""
        return list(rig_verbs(self.plant))

    @property
    def controller_verbs(self) -> list[str]:
        """The controller's scenario verbs the exercise's scenarios use (the Tecomat's ``interrupt``)."""
        used = {a.verb for s in self.exercise.scenarios for a in s.actions if a.rig is not None and a.rig.controller}
        return sorted(used)

    # -- scenarios ------------------------------------------------------------------------------

    def _scenario(self, scenario: Scenario) -> None:
        plant, cpu = self.plant, self.cpu
        assert cpu is not None
        tags = [e.name for e in cpu.table]
        if plant is not None:
            sensors = [n for n, s in plant.signals.items() if s.direction == "sensor"]
            actuators = [n for n, s in plant.signals.items() if s.direction == "actuator"]
            buttons = [n for n, s in plant.signals.items() if s.operator]
            stations = list(stations_of(plant))
        else:
            sensors, actuators, stations = [], [], []
            buttons = list(cpu.inputs)
        signals = sensors + actuators + [t for t in self.wired if t not in sensors + actuators]
        for where, detail in name_problems(
            scenario,
            stations=stations,
            buttons=buttons,
            signals=signals if self.wired else [],
            tags=tags,
            actuators=actuators,
            sensors=sensors,
            **{**plant_vocabulary(plant), "events": self.plant_events},
        ):
            self.add(where, detail)
        for action in scenario.actions:
            if action.verb == "write" and action.target.split(".")[0].split("[")[0] in tags:
                try:
                    cpu.write(action.target, action.args["value"])  # a scratch CPU: types and paths as in a run
                except PlcError as exc:
                    self.add(action.defined_at, f"scenario {scenario.name!r}: {action.describe()}: {exc}")

    # -- checks ---------------------------------------------------------------------------------

    def _hmi(self) -> None:
        """The HMI's controls are Bool tags of the exercise, each a switch or a button."""
        assert self.cpu is not None
        traced = default_signals(self.cpu)
        for tag, kind in self.exercise.hmi.items():
            if kind not in ("switch", "button"):
                self.add(self.exercise.defined_at, f"hmi[{tag!r}] is {kind!r}; a control is 'switch' or 'button'")
            if tag not in traced:
                self.add(
                    self.exercise.defined_at,
                    f"hmi names {tag!r}, which the exercise does not have{did_you_mean(tag, traced)}",
                )

    def _checks(self) -> None:
        ex = self.exercise
        names = [c.name for c in ex.checks]
        for dup in sorted({n for n in names if names.count(n) > 1}):
            self.add(ex.defined_at, f"two checks share the name {dup!r}; name them apart with .named(...)")
        scenario_names = [s.name for s in ex.scenarios]
        for sol in ex.solutions:
            for f in sol.fails:
                if f not in names:
                    self.add(
                        ex.defined_at,
                        f"solution {sol.name} should fail {f!r}, which is not a check{did_you_mean(f, names)}",
                    )
        assert self.cpu is not None
        observed = traced_observables(self.plant)  # the plant's columns in every row (plant:Z.s)
        traced = default_signals(self.cpu) + (observed[0] if observed else [])
        for gc in ex.checks:  # type: ignore[union-attr]
            where = self._where(gc)
            for s in gc.scenarios or ():
                if s not in scenario_names:
                    self.add(
                        where,
                        f"check {gc.name!r} applies to scenario {s!r}, which does not exist"
                        f"{did_you_mean(s, scenario_names)}; scenarios: {_choices(scenario_names)}",
                    )
            self._check(gc.check, f"check {gc.name!r}", gc.scenarios, where, traced)
        self._requirements()
        self._conditions(traced)

    def _requirements(self) -> None:
        """Each check's requirement is words of the task text, and ``requirements`` names only checks."""
        ex = self.exercise
        names = [c.name for c in ex.checks]
        for name in ex.requirements:
            if name not in names:
                self.add(ex.defined_at, f"requirements names {name!r}, which is not a check{did_you_mean(name, names)}")
        task = plain_words(ex.task)
        for gc in ex.checks:  # type: ignore[union-attr]
            if gc.requirement is not None and plain_words(gc.requirement) not in task:
                self.add(
                    self._where(gc),
                    f"check {gc.name!r} grades {gc.requirement!r}, which the task text does not state: quote the "
                    "task's own words, or state the requirement in the task",
                )

    def _conditions(self, traced: list[str]) -> None:
        """The operating conditions quote the task and read names the exercise has; what a scenario declares it leaves
        is a condition (or ``FAULTS``) and the task's words for what must happen then (see
        :mod:`plcsim.check.operating`; whether a scenario leaves one depends on the run, and is tested there)."""
        ex = self.exercise
        task = plain_words(ex.task)
        words = [c.words for c in ex.conditions]
        for condition in ex.conditions:
            if plain_words(condition.words) not in task:
                self.add(
                    condition.defined_at,
                    f"the condition {condition.words!r} is not in the task text: quote the task's own words, or state "
                    "the condition in the task",
                )
            self._check(condition.check, f"condition {condition.words!r}", None, condition.defined_at, traced)
        for scenario in ex.scenarios:
            label = f"scenario {scenario.name!r}"
            for left, said in scenario.outside.items():
                if left != FAULTS and left not in words:
                    self.add(
                        scenario.defined_at,
                        f"{label} declares it leaves {left!r}, which is not a condition of the exercise"
                        f"{did_you_mean(left, words)}; conditions: {_choices([*words, FAULTS])}",
                    )
                if plain_words(said) not in task:
                    self.add(
                        scenario.defined_at,
                        f"{label} leaves {left!r} on the strength of {said!r}, which the task text does not state: "
                        "the task says what must happen then, or the scenario goes",
                    )

    def _where(self, gc: GradedCheck) -> str:
        own = getattr(gc.check, "defined_at", "?")
        return own if own != "?" else (gc.defined_at if gc.defined_at != "?" else self.exercise.defined_at)

    def _check(
        self, check: Check, label: str, scenarios: tuple[str, ...] | None, where: str, traced: list[str]
    ) -> None:
        """The names ``check`` reads (a check applied to ``scenarios``, None: all) exist in the exercise."""
        used = check.names()
        for name in used.signals:
            if name not in traced:
                self.add(
                    where,
                    f"{label} reads {name!r}, which the exercise does not have{did_you_mean(name, traced)}; "
                    f"a check can read: {_choices(traced)}",
                )
        applies = [s for s in self.exercise.scenarios if scenarios is None or s.name in scenarios]
        events, subjects = self.plant_events, self.plant_subjects
        parts = sorted({a.target for s in applies for a in s.actions if a.verb == "place"})
        plant = getattr(self.plant, "name", "(no plant)")
        for kind, subject in used.events:
            if kind not in events:
                self.add(
                    where,
                    f"{label} waits for the plant event {kind!r}, which {plant} never emits"
                    f"{did_you_mean(kind, events)}; its events: {_choices(events)}",
                )
            elif subjects is not None and subject is not None and subject not in parts + subjects:
                named = parts + [s for s in subjects if s not in parts]
                self.add(
                    where,
                    f"{label} waits for {kind!r} of {subject!r}, which is neither a part of its scenarios nor "
                    f"a name in {plant}{did_you_mean(subject, named)}; valid: {_choices(named)}",
                )
        for verb, target in used.actions:
            self._action(label, where, verb, target, applies)
        for task in used.tasks:
            if not _TASK.fullmatch(task):
                self.add(where, f"{label} counts calls of {task!r}; name a task as 'OB30'")
        self._spans(check, label, where)
        if isinstance(check, Quantity):
            for bound in (check.lo, check.hi):
                if isinstance(bound, str):
                    try:
                        Span.parse(bound)
                    except PlcError as exc:
                        self.add(where, f"{label}: bound {bound!r}: {exc}")
            numbers = [b for b in (check.lo, check.hi) if isinstance(b, (int, float))]
            if len(numbers) == 2 and numbers[0] > numbers[1]:
                self.add(where, f"{label}: the bounds {check.lo} and {check.hi} run backwards; no value lies between")

    def _spans(self, check: Check, label: str, where: str) -> None:
        """Durations and windows: none negative for every scan time, none running backwards."""
        negative = [s for s in _spans_of(check) if s.ns <= 0 and s.scans <= 0 and (s.ns or s.scans)]
        for span in negative:
            self.add(where, f"{label}: the duration {str(span)!r} is negative; durations count forwards")
        if negative:
            return
        pairs = [
            (getattr(check, "lo", None), getattr(check, "hi", None)),
            getattr(check, "window", None) or (None, None),
        ]
        for lo, hi in pairs:
            if isinstance(lo, Span) and isinstance(hi, Span) and lo.scans == hi.scans and hi.ns < lo.ns:
                self.add(where, f"{label}: the window from {lo} to {hi} runs backwards")

    def _action(self, label: str, where: str, verb: str, target: str | None, applies: list[Scenario]) -> None:
        if verb == "action failed":
            return
        verbs = [*VERBS, *self.plant_verbs, *self.controller_verbs]
        if verb not in verbs:
            self.add(
                where,
                f"{label} counts the scenario action {verb!r}, which is not an action"
                f"{did_you_mean(verb, verbs)}; actions: {_choices(verbs)}",
            )
            return
        done = sorted({a.target for s in applies for a in s.actions if a.verb == verb})
        if (target is None and done) or target in done:
            return
        which = f"{verb} {target}" if target is not None else verb
        if not done:
            self.add(where, f"{label} looks for the action {which!r}, but none of its scenarios does {verb}")
            return
        self.add(
            where,
            f"{label} looks for the action {which!r}, which none of its scenarios does"
            f"{did_you_mean(target or '', done)}; they {verb}: {_choices(done)}",
        )


def plain_words(text: str) -> str:
    """``text`` as a requirement is looked up in a task: lower case, any run of white space one space.

    >>> plain_words("The belt  stops\\nat S2.")
    'the belt stops at s2.'
    """
    return " ".join(text.split()).lower()


def _spans_of(check: Check) -> Iterator[Span]:
    """The durations a check holds (reaction windows, tolerances, deadlines, time windows)."""
    if not dataclasses.is_dataclass(check):
        return
    for f in dataclasses.fields(check):
        value = getattr(check, f.name)
        for item in value if isinstance(value, tuple) else (value,):
            if isinstance(item, Span):
                yield item
