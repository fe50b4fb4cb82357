"""A scenario as a whole: the named timeline of actions with its duration, and the times drawn for one run.

:class:`Scenario` is what an exercise lists; :func:`plan` draws its seeded time ranges (``"2s..3s"``) for one
run, in the order the actions were written, and the runner (:mod:`plcsim.scenario.runner`) carries them out.
"""

from __future__ import annotations

import random
from collections.abc import Iterable, Mapping
from dataclasses import dataclass
from typing import Any

from plcsim.core.errors import defined_at
from plcsim.core.literals import format_ns, to_ns
from plcsim.scenario.verbs import Action, ScenarioError, parse_at_line


def _flatten(items: Iterable[Any]) -> list[Action]:
    out: list[Action] = []
    for item in items:
        if isinstance(item, Action):
            out.append(item)
        elif isinstance(item, (list, tuple)):
            out.extend(_flatten(item))
        else:
            raise ScenarioError(f"a scenario holds actions such as press(...) or place(...), not {item!r}")
    return out


FAULTS = "faults"
"""The key of :attr:`Scenario.outside` for a scenario that injects a fault (an action whose ``fault`` is True)."""


class Scenario:
    """A named timeline of actions with a duration and a short description.

    ``outside`` declares the operating conditions of the task the scenario deliberately leaves, each with the words
    of the task that say what must happen then: ``{"the operator loads one object at a time": "If a second object
    is loaded ..."}``; the key :data:`FAULTS` for a scenario that injects a fault (``{FAULTS: "If the object does
    not reach S2 within 10 s, ..."}``). The exercise refuses to load words its task does not state; a fault or a
    condition left undeclared is found on a run (see :mod:`plcsim.check.operating`).
    """

    def __init__(
        self,
        name: str,
        *actions: Action | list[Action],
        duration: str | int = "10s",
        description: str = "",
        outside: Mapping[str, str] | None = None,
    ):
        self.name = name
        self.actions = _flatten(actions)
        self.defined_at = defined_at()
        self.duration_ns = parse_at_line(lambda d: to_ns(d, "duration"), duration, f"scenario {name!r}")
        self.description = description
        self.outside = dict(outside or {})
        if self.duration_ns <= 0:
            raise ScenarioError(
                f"{self.defined_at}: scenario {name!r}: duration {duration!r} is not positive; "
                f"a run needs a duration such as duration='10s'"
            )
        for a in self.actions:
            if a.t is not None and a.t.hi_ns >= self.duration_ns:
                raise ScenarioError(
                    f"{a.defined_at}: scenario {name!r}: {a.describe()}: the run ends at "
                    f"{format_ns(self.duration_ns)}, so this action may never happen; "
                    f"make it earlier or the duration longer"
                )

    @property
    def faults(self) -> list[Action]:
        """The actions that inject a fault."""
        return [a for a in self.actions if a.fault]

    def __repr__(self) -> str:
        return f"<Scenario {self.name}: {len(self.actions)} actions, {format_ns(self.duration_ns)}>"


@dataclass
class Planned:
    """An action with its drawn time (or its trigger still pending)."""

    action: Action
    at_ns: int | None
    order: int
    done: bool = False
    armed_since: int | None = None


def plan(scenario: Scenario, rng: random.Random) -> list[Planned]:
    """Draw the random times of a scenario (in the order the actions were written)."""
    planned: list[Planned] = []
    starts: dict[int, int] = {}
    for order, action in enumerate(scenario.actions):
        if action.verb == "release" and "after" in action.args:
            start = starts[id(action.args["after"])]
            at = start + action.args["hold"].draw(rng)
        elif action.t is not None:
            at = action.t.draw(rng)
        else:
            at = None
        if at is not None:
            starts[id(action)] = at
        planned.append(Planned(action, at, order))
    return planned
