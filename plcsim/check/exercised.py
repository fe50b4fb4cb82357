"""Which checks a submission exercised: points only for behaviour the scenarios showed.

A safety check (``never(all_of("D1", ...))``, ``always(implies("S2", off("D1")))``, "no false
alarm") holds trivially for a program that does nothing: the belt that never runs never runs at the
wrong time. Such a pass proves nothing, so it earns nothing; it is reported as *not exercised*
(0 points, counted in the maximum), never as a failure of what the check states.

Two rules decide, the first for every check, the second where the exercise asks for it:

* **generic**: a check counts only if the program drove, in at least one graded scenario, one of
  the signals the check guards: the signals it reads that a program writes (outputs, memory and DB
  tags, instance members; not inputs, not the tags a scenario presses or writes itself). A check
  that reads no such signal (``never(event("part fell off"))``, a static check) counts if the
  program drove any signal at all. "Drove" means the signal changed during the run, or an output
  was on from the first scan. The rule looks at all graded scenarios together, not at each on its
  own, because staying still is the right behaviour in some of them (4.3.5 "placed at S2"; ALARM
  in the alarm exercise's normal run): what it asks is that the program has shown it can move
  what the check guards. A program that does nothing, or whose CPU stops at once, earns nothing.
* **per check** (opt-in): ``check.exercised_by(rises("D3"))`` counts the check only in scenarios
  in which that occurrence happened (or that condition held in some scan), for a check whose
  point is a behaviour one scenario may fail to provoke.

>>> from plcsim.check import always, implies, off
>>> from plcsim.trace.facade import Trace
>>> kinds = {"S2": "input", "D1": "output", "H1": "output"}
>>> tr = Trace(list(kinds), kinds=kinds, types=dict.fromkeys(kinds, "bool"))
>>> for k in range(3):
...     tr.add_row(k * 1_000_000, (k + 1) * 1_000_000, 1, (k == 2, False, k == 1))
>>> activity = Activity.of([tr], written_by_scenario=set())
>>> activity.unexercised(always(implies("S2", off("D1")))), activity.unexercised(always(off("H1")))
('the program never drove D1 in any scenario', None)
"""

from __future__ import annotations

from collections.abc import Iterable, Sequence
from dataclasses import dataclass

import numpy as np

from plcsim.check.base import Check, Context
from plcsim.check.occurrences import Occurrences
from plcsim.check.static import StaticCheck
from plcsim.trace.facade import Trace

SCENARIO_WRITES = frozenset({"press", "release", "switch", "write"})
"""Scenario actions that set a tag themselves (an HMI button, a written value): not the program's doing."""


@dataclass(frozen=True)
class Activity:
    """What the program drove over the graded runs: the signals it could write, and those it did."""

    writable: frozenset[str]
    driven: frozenset[str]

    @classmethod
    def of(cls, traces: Iterable[Trace], *, written_by_scenario: set[str]) -> Activity:
        writable: set[str] = set()
        driven: set[str] = set()
        for trace in traces:
            for name in trace.names:
                if trace.kinds.get(name) == "input" or name in written_by_scenario:
                    continue
                writable.add(name)
                if name not in driven and _drove(trace, name):
                    driven.add(name)
        return cls(frozenset(writable), frozenset(driven))

    def unexercised(self, check: Check) -> str | None:
        """Why the generic rule does not count ``check`` (None: it counts)."""
        if not self.driven:
            return "the program drove no output or tag in any scenario"
        if isinstance(check, StaticCheck):
            return None
        guarded = [s for s in check.names().signals if s in self.writable]
        if guarded and not any(s in self.driven for s in guarded):
            return f"the program never drove {', '.join(guarded)} in any scenario"
        return None


def _drove(trace: Trace, name: str) -> bool:
    if not len(trace):
        return False
    column = trace.column(name)
    if bool(np.any(column != column[0])):
        return True
    return trace.kinds.get(name) == "output" and bool(column[0])


def scenario_writes(scenarios: Sequence[object]) -> set[str]:
    """The tags the scenarios' own actions press or write (``press("ACK")``)."""
    return {a.target for s in scenarios for a in getattr(s, "actions", ()) if a.verb in SCENARIO_WRITES}


def unprovoked(check: Check, ctx: Context) -> str | None:
    """Why the check's own ``exercised_by`` condition does not count it in this run (None: it counts)."""
    wanted = check.exercise_conditions
    if not wanted:
        return None
    for what in wanted:
        if isinstance(what, Occurrences):
            if len(what.times(ctx)):
                return None
        elif bool(np.any(what.rows(ctx))):
            return None
    return f"{' or '.join(w.describe() for w in wanted)} never happened in this scenario"
