"""An exercise: the task, its I/O table and data blocks, the rig and wiring, scenarios, checks and
the textbook's solutions (the reference and the deliberately wrong ones).

Exercises are data plus a little code; they live in the top-level ``exercises`` package and are
found by their textbook number (``4.3.6``) or slug (``conveyor-2``).
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from plcsim.check import Check, OperatingCondition
from plcsim.controllers.choice import controller_for
from plcsim.controllers.loaded import SourceProgram
from plcsim.core.errors import ConfigurationError, ExerciseError, defined_at
from plcsim.exercise.validation import plain_words, validate
from plcsim.frontends import read_program
from plcsim.plant.protocol import Plant
from plcsim.scenario.planning import Scenario
from plcsim.sim.simulation import Pacing, Simulation
from plcsim.sim.wiring import Wire
from plcsim.tags.table import DataBlock, Tag, TagTable
from plcsim.tags.types import type_by_name


@dataclass(frozen=True)
class IO:
    """One row of an exercise's I/O table (the textbook's tag table).

    Attributes:
        tag: the tag name as in the textbook (``TLACIDLO``).
        gloss: what it means in English (``push-button``).
        type: the S7 type name (``Bool``).
        address: the absolute address (``%I0.0``), or None for a symbolic HMI/DB tag.
        wiring: ``NO`` or ``NC`` for a sensor, None otherwise.
        signal: the plant signal wired to it (defaults to the tag name for inputs and outputs).
        comment: provenance or a note (``address proposed; not in the textbook``).
    """

    tag: str
    gloss: str
    type: str = "Bool"
    address: str | None = None
    wiring: str | None = None
    signal: str | None = None
    comment: str = ""

    @property
    def direction(self) -> str:
        if self.address is None:
            return "memory"
        area = self.address.lstrip("%")[0].upper()
        return {"I": "input", "Q": "output"}.get(area, "memory")


@dataclass(frozen=True)
class Solution:
    """A program shipped with an exercise.

    Attributes:
        name: ``reference``, ``solution-2``, ``wrong-4`` ...
        path: the program file.
        kind: ``reference`` (must pass every check), ``alternative`` (also correct) or ``wrong``.
        explanation: what the solution shows; for a wrong one, the textbook's explanation of its flaw.
        fails: for a wrong solution, the names of the checks that expose its flaw (it must fail them).
        scenarios: the scenarios this solution is graded on (None: all).
    """

    name: str
    path: Path
    kind: str = "reference"
    explanation: str = ""
    fails: tuple[str, ...] = ()
    scenarios: tuple[str, ...] | None = None

    def program(self) -> SourceProgram:
        """The solution's program, read by the front end its file suffix names."""
        return read_program(self.path)


@dataclass
class GradedCheck:
    """A check, its points and the scenarios it applies to (None: all)."""

    check: Check
    scenarios: tuple[str, ...] | None = None
    defined_at: str = "?"
    requirement: str | None = None
    """The words of the task the check grades: the exercise's ``requirements[name]``, else the check's own
    (:meth:`~plcsim.check.Check.grades`)."""

    @property
    def name(self) -> str:
        return self.check.title


def only(check: Check, *scenarios: str) -> GradedCheck:
    """Apply a check only in some scenarios: ``only(never(...), "normal", "two parts")``."""
    return GradedCheck(check, tuple(scenarios), defined_at())


@dataclass
class Exercise:
    """Everything needed to run and grade one exercise.

    It is validated when built (see :mod:`plcsim.exercise.validation`): a name that its tags, wiring or plant
    lack, a check on a scenario that does not exist, raise :class:`~plcsim.core.errors.ExerciseError`
    naming the file and line, so the instructor's mistake never reaches a student's grade.

    ``spec_equivalent`` declares the mutants of the reference (``plcsim mutate``) that are correct
    programs by the spec's words, each with the reason: ``{"OB1: network takt moved to the end":
    "the pulse used one scan later is still one a second"}`` (a key is a mutant's description, or
    ``"line N: description"`` where the description alone names several). Mutation testing reports
    them as explained, outside the score; one that matches no mutant, or is killed, is reported.

    ``hmi`` is the operator panel the task describes where its controls are tags, not plant signals (the HMI
    bits of a data block): each Bool tag named is offered on the live page as a ``"switch"`` (a click flips it)
    or a ``"button"`` (TRUE while held): ``{"DB_SKIP.AUTO": "switch", "DB_SKIP.MAN_HORE": "button"}``.

    ``requirements`` names, per check name, the words of the task text the check grades (for checks built by
    a helper that several exercises share; a check of one exercise can say it itself with ``.grades(...)``).
    Each must be in the task text, or the exercise does not load: a check grades only what the task states.

    ``conditions`` are the operating conditions the task states (:func:`~plcsim.check.operating.assumes`: the
    task's words and a check a run inside them passes), such as "Only one object is on the conveyor at a time".
    A scenario that leaves one declares it in ``Scenario(outside={words: ...})`` with the task's words for what
    must happen then, as one that injects a fault declares ``FAULTS``; the words must be in the task text.

    ``aliases`` are the other names the textbook gives a tag or a data-block member (``{"Dopravník":
    "D1_VPRED", "DATA.POZ3_OBS_Farba 1": "DATA.POZ3_OBS_Farba1"}``): a program may use either; a name with a
    space is also accepted with ``_`` for the space (see :meth:`~plcsim.tags.table.TagTable.add_alias`).
    """

    number: str
    slug: str
    title: str
    task: str
    io: Sequence[IO]
    rig: Callable[[], Plant] | None
    scenarios: Sequence[Scenario]
    checks: Sequence[Check | GradedCheck]
    solutions: Sequence[Solution]
    title_sk: str = ""
    dbs: Mapping[str, DataBlock] = field(default_factory=dict)
    cpu: Mapping[str, Any] = field(default_factory=dict)
    scenario_cpu: Mapping[str, Mapping[str, Any]] = field(default_factory=dict)
    dt: str = "1ms"
    record_changes_only: bool = False
    notes: str = ""
    plant_name: str = ""
    spec_equivalent: Mapping[str, str] = field(default_factory=dict)
    hmi: Mapping[str, str] = field(default_factory=dict)
    cpu_budget_s: float | None = None
    """The CPU seconds a graded submission may use in all scenarios together; None (the default): ten times
    what the reference uses, measured once per batch, at least 10 s (:mod:`plcsim.grading.sandbox.limits`)."""
    requirements: Mapping[str, str] = field(default_factory=dict)
    aliases: Mapping[str, str] = field(default_factory=dict)
    conditions: Sequence[OperatingCondition] = ()

    def __post_init__(self) -> None:
        self.defined_at = defined_at()
        for mutant, reason in self.spec_equivalent.items():
            if not (isinstance(reason, str) and reason.strip()):
                raise ExerciseError(f"{self.defined_at}: spec_equivalent[{mutant!r}] needs the reason it is correct")
        budget = self.cpu_budget_s
        if budget is not None and (isinstance(budget, bool) or not isinstance(budget, int | float) or not budget > 0):
            raise ExerciseError(f"{self.defined_at}: cpu_budget_s is a positive number of seconds, not {budget!r}")
        self.checks = [c if isinstance(c, GradedCheck) else GradedCheck(c) for c in self.checks]
        for gc in self.checks:
            gc.requirement = self.requirements.get(gc.name) or gc.check.requirement
        validate(self)

    def requirement_list(self) -> list[tuple[str, list[GradedCheck]]]:
        """The requirements the checks grade, in the order the task states them, each with its checks."""
        by_words: dict[str, list[GradedCheck]] = {}
        for gc in self.checks:  # type: ignore[union-attr]
            if gc.requirement:
                by_words.setdefault(gc.requirement, []).append(gc)
        task = plain_words(self.task)
        return sorted(by_words.items(), key=lambda item: task.find(plain_words(item[0])))

    # -- building a run -----------------------------------------------------------------------

    def tag_table(self) -> TagTable:
        """The exercise's tags: its I/O table and data blocks (a fresh copy of the table built once for
        them, so that the data blocks' types are the same objects in every simulation and a program
        compiled for one scenario is reused in the next: see :meth:`Program.compile`)."""
        key = (tuple(self.io), tuple(self.dbs.items()), tuple(self.aliases.items()))
        cached = self.__dict__.get("_tag_table")
        if cached is None or cached[0] != key:
            cached = self.__dict__["_tag_table"] = (key, self._build_tag_table())
        return cached[1].copy()

    def _build_tag_table(self) -> TagTable:
        table = TagTable()
        for row in self.io:
            dtype = type_by_name(row.type)
            if row.address is None:
                table.add(row.tag, dtype(), source=f"exercise {self.number}")  # type: ignore[operator]
            else:
                table.add(row.tag, Tag(row.address, dtype), source=f"exercise {self.number}")  # type: ignore[arg-type]
        for name, db in self.dbs.items():
            table.add(name, db, source=f"exercise {self.number}")
        for alias, name in self.aliases.items():
            table.add_alias(alias, name)
        return table

    def wires(self) -> list[Wire]:
        """The wiring implied by the I/O table (sensors with their NO/NC contact, outputs)."""
        out = []
        for row in self.io:
            if row.direction in ("input", "output") and (row.signal or row.wiring or row.direction == "output"):
                out.append(Wire(row.signal or row.tag, row.tag, row.wiring or "NO"))
        return out

    def scenario(self, name: str) -> Scenario:
        for s in self.scenarios:
            if s.name == name:
                return s
        raise ConfigurationError(
            f"exercise {self.number} has no scenario {name!r}; scenarios: {', '.join(s.name for s in self.scenarios)}"
        )

    def solution(self, name: str) -> Solution:
        for s in self.solutions:
            if s.name == name:
                return s
        raise ConfigurationError(
            f"exercise {self.number} has no solution {name!r}; solutions: {', '.join(s.name for s in self.solutions)}"
        )

    @property
    def reference(self) -> Solution:
        return next(s for s in self.solutions if s.kind == "reference")

    def checks_for(self, scenario: str) -> list[GradedCheck]:
        return [c for c in self.checks if c.scenarios is None or scenario in c.scenarios]  # type: ignore[union-attr]

    def simulation(
        self,
        program: SourceProgram,
        scenario: Scenario | str,
        *,
        seed: int = 0,
        pacing: Pacing | None = None,
        geometry: bool = True,
        **cpu_options: Any,
    ) -> Simulation:
        """A ready-to-run simulation of ``program`` (any front end's) on this exercise's rig and scenario;
        ``pacing`` as in :class:`~plcsim.sim.simulation.Simulation` (None: as fast as it goes); ``geometry``
        False samples no shapes for drawing (a run nobody will watch: grading without a recording)."""
        if isinstance(scenario, str):
            scenario = self.scenario(scenario)
        options = {**self.cpu, **self.scenario_cpu.get(scenario.name, {}), **cpu_options}
        cpu = controller_for(program, self.tag_table(), seed=seed, **options)
        plant = self.rig() if self.rig is not None else None
        wires = self.wires() if plant is not None else None
        drawing = {} if geometry else {"geometry_hz": 0}
        return Simulation(
            cpu,
            plant,
            wires,
            scenario,
            dt=self.dt,
            seed=seed,
            changes_only=self.record_changes_only,
            pacing=pacing,
            **drawing,
        )

    def describe_io(self) -> list[dict[str, str]]:
        """The I/O table as rows for printing."""
        return [
            {
                "tag": r.tag,
                "gloss": r.gloss,
                "type": r.type,
                "address": r.address or "-",
                "direction": r.direction,
                "wiring": r.wiring or "-",
                "comment": r.comment,
            }
            for r in self.io
        ]
