"""The simulation a live session (or its replay) runs: an exercise's, or a bare rig wired by signal name."""

from __future__ import annotations

import pkgutil
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from plcsim.controllers.choice import controller_for
from plcsim.controllers.loaded import SourceProgram
from plcsim.controllers.profiles import all_profiles
from plcsim.core.clock import NEVER
from plcsim.core.errors import PlcError
from plcsim.frontends import read_program
from plcsim.plant.protocol import Plant
from plcsim.plant.verbs import RigVerb
from plcsim.scenario.planning import Scenario
from plcsim.sim.simulation import Pacing, Simulation
from plcsim.sim.wiring import Wire
from plcsim.tags.table import Tag

LIVE = "live"
"""The scenario name of a live session with no base scenario."""
REPLAY_LIMIT_NS = 3_600_000_000_000
"""How long a saved scenario may run on a target without ``--seconds``: an hour of simulated time (or the exercise's
longest scenario, if longer). A file from a page or a student must not make a run go on without bound."""


@dataclass
class Target:
    """What a session runs on: an exercise (with its checks and scenarios) or a bare rig."""

    name: str
    exercise: Any = None
    rig: Any = None

    @classmethod
    def find(cls, name: str) -> Target:
        """An exercise by number, slug or file, or a rig by its id (``PANEL``, ``CONV1``)."""
        from plcsim.core.registry import is_rig, rig, rig_names
        from plcsim.exercise.catalog import get

        if is_rig(name):
            key = next(k for k in rig_names() if k.upper() == name.upper())
            return cls(key, rig=rig(key))

        exercise = get(name)
        return cls(exercise.number, exercise=exercise)

    def verbs(self) -> dict[str, RigVerb]:
        """The scenario verbs a session on this target may use besides :mod:`plcsim.scenario.verbs`'s: its rig's
        (``set_ambient``) and every registered controller's (the Tecomat's ``interrupt``, ``set_clock``)."""
        rig = self.exercise.rig if self.exercise is not None else self.rig
        found: dict[str, RigVerb] = {}
        for p in all_profiles():
            found.update(getattr(pkgutil.resolve_name(p.controller), "VERBS", {}))
        found.update(getattr(rig, "VERBS", {}) if rig is not None else {})
        return found

    def replay_limit_ns(self) -> int:
        """The longest a saved scenario may run here: :data:`REPLAY_LIMIT_NS`, or the exercise's longest scenario."""
        scenarios = self.exercise.scenarios if self.exercise is not None else ()
        return max([REPLAY_LIMIT_NS, *(s.duration_ns for s in scenarios)])

    def base(self, name: str | None) -> Scenario | None:
        """The exercise's scenario ``name`` (None: none); a rig has none."""
        if name is None:
            return None
        if self.exercise is None:
            raise PlcError(f"the rig {self.name} has no scenarios; a live session on it starts from nothing")
        return self.exercise.scenario(name)

    def simulation(
        self, program: SourceProgram | str | Path, scenario: Scenario, *, seed: int, pacing: Pacing | None = None
    ) -> Simulation:
        """A simulation of ``program`` (a file or a read program) on this target, running ``scenario``."""
        source = read_program(program) if isinstance(program, (str, Path)) else program
        if self.exercise is not None:
            return self.exercise.simulation(source, scenario, seed=seed, pacing=pacing)
        return rig_simulation(self.rig(), source, scenario, seed=seed, pacing=pacing)


def rig_simulation(
    plant: Plant,
    program: SourceProgram,
    scenario: Scenario | None = None,
    *,
    seed: int = 1,
    cycle: str | None = None,
    pacing: Pacing | None = None,
) -> Simulation:
    """A bare rig wired by name: each Bool sensor a tag ``%I`` and each Bool actuator a tag ``%Q`` of the same
    name, in the order the plant declares them (``S1`` → ``%I0.0``, ``S2`` → ``%I0.1``, ``D1`` → ``%Q0.0``)."""
    tags: dict[str, Tag] = {}
    wires = []
    n_in = n_out = 0
    for name, spec in plant.signals.items():
        if spec.kind != "bool":
            continue
        if spec.direction == "sensor":
            tags[name] = Tag(f"%I{n_in // 8}.{n_in % 8}")
            n_in += 1
        else:
            tags[name] = Tag(f"%Q{n_out // 8}.{n_out % 8}")
            n_out += 1
        wires.append(Wire(name, name))
    options = {"cycle": cycle} if cycle else {}
    cpu = controller_for(program, tags, clock_memory_byte=100, system_memory_byte=101, seed=seed, **options)
    return Simulation(cpu, plant, wires, scenario, seed=seed, pacing=pacing)


def open_ended(name: str, base: Scenario | None) -> Scenario:
    """The scenario a live session starts with: ``base``'s actions and no end (the student ends it)."""
    return Scenario(name, *(base.actions if base is not None else ()), duration=NEVER, description="live session")
