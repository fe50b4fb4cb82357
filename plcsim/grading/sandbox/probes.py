"""The trusted probe: what the run of each scenario must look like, from a probe program the grader runs itself.

A child's result is validated against it (:func:`plcsim.grading.run_result.decode`): the signals, kinds
and types of the exercise's trace, the scenario's length and the most rows a run can have. A batch
probes once per scenario (:class:`Probes`) instead of once per submission.
"""

from __future__ import annotations

import copy
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import Any

from plcsim.exercise.model import Exercise
from plcsim.frontends.python.program import Program
from plcsim.grading.run_result import Expected

_PROBE_PROGRAM = "def OB1(t):\n    pass\n"


@dataclass(frozen=True)
class Probes:
    """The trusted probe's results of one batch, computed once per (exercise, scenario, seed) in the
    grader (:meth:`of`) instead of once per submission.

    Each submission is validated against its own deep copy (:meth:`expected`), so nothing done while
    grading one submission can change what the next is checked against; what a child sends never
    reaches them. A scenario or seed the batch did not probe is probed afresh.
    """

    exercise: str
    seed: int
    by_scenario: Mapping[str, Expected]
    """Scenario name -> what its run must look like."""

    @classmethod
    def of(cls, exercise: Exercise, scenarios: Sequence[Any], seed: int) -> Probes:
        return cls(exercise.number, seed, {s.name: _expected(exercise, s, seed) for s in scenarios})

    def expected(self, exercise: Exercise, scenario: Any, seed: int) -> Expected:
        """What the run of ``scenario`` must look like: a copy of the cached probe, or a fresh probe."""
        ours = (exercise.number, seed) == (self.exercise, self.seed)
        cached = self.by_scenario.get(scenario.name) if ours else None
        return copy.deepcopy(cached) if cached is not None else _expected(exercise, scenario, seed)


def _expected(exercise: Exercise, scenario: Any, seed: int) -> Expected:
    """What the run of ``scenario`` must look like, from a trusted probe program on the same CPU and rig."""
    sim = exercise.simulation(Program.from_source(_PROBE_PROGRAM, "<probe>"), _for_the_probe(scenario), seed=seed)
    trace = sim.trace
    step = max(1, min(sim.dt_ns, trace.meta.get("cycle_ns") or sim.dt_ns))
    duration = scenario.duration_ns
    max_rows = max(4 * (duration // step + 1), 2 * (duration // 100_000 + 1)) + 10_000
    meta = {k: v for k, v in trace.meta.items() if k not in ("end_ns", "scans", "program")}
    return Expected(scenario.name, duration, max_rows, dict(trace.kinds), dict(trace.types), meta)


def _for_the_probe(scenario: Any) -> Any:
    """``scenario`` without the verbs a controller brings (the Tecomat's ``set_clock``, ``interrupt``): the
    probe runs on the S7, which cannot carry them out, and they change what a program reads, never the
    shape of the trace the probe is asked for."""
    kept = [a for a in scenario.actions if a.rig is None or not a.rig.controller]
    if len(kept) == len(scenario.actions):
        return scenario
    probe = copy.copy(scenario)
    probe.actions = kept
    return probe
