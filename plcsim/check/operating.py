"""Operating conditions: what a task assumes of the operator and the machine, so that no scenario grades a
student on a situation the task rules out without saying what must happen then.

A condition quotes the task sentence that states it and is a check over a scenario's run that passes while the
run stays inside it::

    Exercise(..., conditions=[assumes("Only one object is on the conveyor at a time", parts_at_once(1))])

A scenario that deliberately leaves a condition declares it, with the task words that say what must happen then:
``Scenario(..., outside={"Only one object is on the conveyor at a time": "A second object loaded while ..."})``.
A scenario that injects a fault (``jam``, ``stuck``, a rig verb declared ``fault=True``) is outside the machine's
normal operation: it declares :data:`~plcsim.scenario.planning.FAULTS` with the task words that speak of the fault.

The exercise checks the words when it is loaded (:mod:`plcsim.exercise.validation`); whether a scenario stays
inside the conditions depends on the run, so :func:`undeclared_breaks` reads a run of the reference, and
:func:`fault_problems` the faults (tests/course/test_operating_conditions.py does both for every shipped exercise).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

from plcsim.check.base import Check, Context
from plcsim.check.quantities import Quantity
from plcsim.core.errors import defined_at
from plcsim.scenario.planning import FAULTS, Scenario
from plcsim.trace.facade import Trace

GONE = ("part removed", "part fell off", "part knocked off")
"""The plant events after which a part is no longer in the machine."""


@dataclass
class OperatingCondition:
    """A condition the task states (``words``, quoted from the task) and the check that passes while a run keeps it."""

    words: str
    check: Check
    defined_at: str = field(default_factory=defined_at)

    def holds(self, trace: Trace) -> tuple[bool, str]:
        """Whether the run kept the condition, and what the check says (a run that gives the check nothing to check,
        such as one object for a spacing, keeps it)."""
        verdict = self.check.evaluate(Context.of(trace))
        return verdict.passed or verdict.nothing_to_check, verdict.message


def assumes(words: str, check: Check) -> OperatingCondition:
    """The condition the task states in ``words``, kept in a run where ``check`` passes:
    ``assumes("Only one object is on the conveyor at a time", parts_at_once(1))``."""
    return OperatingCondition(words, check.named(check.name or f"the task assumes: {words}"), defined_at())


def parts_at_once(at_most: int) -> Quantity:
    """The number of objects in the machine at once, from a ``part placed`` event until the part is removed, falls
    or is knocked off, is at most ``at_most``."""

    def most(ctx: Context) -> tuple[float, list[int]]:
        present: set[str] = set()
        peak, when = 0, 0
        for e in sorted(ctx.trace.events_of("part placed") + _gone(ctx.trace), key=lambda e: e.t_ns):
            part = e.part or e.subject
            if e.kind == "part placed":
                present.add(part)
                if len(present) > peak:
                    peak, when = len(present), e.t_ns
            else:
                present.discard(part)
        return float(peak), [when]

    return Quantity("the number of objects in the machine at once", most, []).at_most(at_most)


def _gone(trace: Trace) -> list[Any]:
    return [e for kind in GONE for e in trace.events_of(kind)]


def fault_problems(scenario: Scenario) -> list[str]:
    """What is wrong with ``scenario``'s declaration of faults: one it injects without declaring :data:`FAULTS` with
    the task's words, or one it declares and does not inject."""
    faults = scenario.faults
    if faults and FAULTS not in scenario.outside:
        return [
            f"scenario {scenario.name!r} injects a fault ({faults[0].describe()}, {faults[0].defined_at}) and does not "
            "say which words of the task speak of it: declare outside={FAULTS: the task's words for what must happen "
            "then}, or state it in the task"
        ]
    if FAULTS in scenario.outside and not faults:
        return [f"scenario {scenario.name!r} declares a fault but injects none: drop outside[FAULTS]"]
    return []


def undeclared_breaks(conditions: list[OperatingCondition], scenario: Scenario, trace: Trace) -> list[str]:
    """What is wrong with ``scenario``'s declarations, read on ``trace`` (a run of the reference): its faults
    (:func:`fault_problems`), each condition the run broke that the scenario does not declare in ``outside``, and
    each it declares that the run kept."""
    out = fault_problems(scenario)
    for condition in conditions:
        kept, message = condition.holds(trace)
        declared = condition.words in scenario.outside
        if not kept and not declared:
            out.append(
                f"scenario {scenario.name!r} leaves the condition the task states, {condition.words!r} ({message}), "
                "and does not say so: keep the scenario inside it, or declare outside={words: the task's words "
                "for what must happen then}"
            )
        elif kept and declared:
            out.append(
                f"scenario {scenario.name!r} declares it leaves {condition.words!r}, but the run kept it: "
                "drop the declaration, or make the scenario do what it says"
            )
    return out


__all__ = ["FAULTS", "GONE", "OperatingCondition", "assumes", "fault_problems", "parts_at_once", "undeclared_breaks"]
