"""The checker language: temporal statements over a trace, written the way an instructor thinks.

>>> conveyor_checks = [
...     rises("D1").within("1 scan").after(rises("S1")),
...     falls("D1").within("1 scan").after(rises("S2")),
...     never(all_of("D1", "S2")).named("belt stopped while a part is at S2"),
...     never(event("part fell off")),
... ]
>>> conveyor_checks[0].describe()
'D1 rises within 1 scan after S1 rises'

Building blocks:

* **occurrences** (points in time): ``rises("D1")``, ``falls("D1")``, ``event("part entered", "S2")``,
  ``action("press", "ACK")`` (a scenario action), ``becomes(condition)``, ``calls("OB30")`` (the
  starts of an interrupt task), ``either(a, b)``, ``seen(action("write", "NULUJ"))`` (the starts of the
  scans that saw it: a tolerance counts from the scan that read the cause, not from the cause). An
  edge needs a scan before it: a signal already TRUE in the first scan has not risen (check it with
  ``eventually(...).before(...)``).
* **conditions** (true or false in each scan): a tag name (``"D1"`` means D1 is TRUE), ``off("D1")``,
  ``value("CISLO") > 0``, ``all_of(...)``, ``any_of(...)``, ``not_(...)``, ``implies(a, b)``,
  ``same("LED", "TLACIDLO")``.
* **checks**: ``X.within(d).after(Y)``, ``X.between(lo, hi).after(Y)``, ``never(c)``, ``always(c)``,
  ``holds(c).until(Y)``, ``holds(c).to_the_end()``, ``holds(c).for_at_least(d)``, ``eventually(c).before(t)``,
  ``count(X)``, ``spacing(X)``, ``durations(c)``, ``duty(c)``, ``final("MOTOR.SEKUNDY")``, ``program_uses_no("SET")``,
  ``event_data(kind, key)`` for a plant's own measurement (the data of its events),
  and ``measure(label, fn)`` for a number computed from the trace by a Python function.
* **operating conditions** (what the task assumes, not graded): ``assumes("task words", check)``,
  ``parts_at_once(1)``; see :mod:`plcsim.check.operating`.

Durations are literals with scans: ``"1 scan"``, ``"10s + 2 scans"``, ``"0.5s - 1 scan"`` (a scan is the
CPU's cycle time). Conditions are evaluated per scan on the values of that scan: an input as the
scan read it, an output as the scan wrote it, so ``always(implies("S2", off("D1")))`` says "in every
scan that saw S2, D1 was written FALSE", i.e. the reaction comes within one scan.
A failed check says what was expected, what happened and when, and names the signals to plot.
"""

from __future__ import annotations

from collections.abc import Iterable
from typing import Any

from plcsim.check.base import Check, Context, Span, Verdict
from plcsim.check.conditions import (
    AllOf,
    AnyOf,
    Compare,
    Condition,
    Not,
    On,
    Value,
    all_of,
    any_of,
    as_condition,
    implies,
    not_,
    off,
    on,
    same,
    value,
)
from plcsim.check.occurrences import (
    Becomes,
    Calls,
    Edge,
    Either,
    EventOccurrences,
    Occurrences,
    Response,
    ResponseBuilder,
    Seen,
    action,
    becomes,
    calls,
    either,
    event,
    falls,
    rises,
    seen,
    seen_at,
)
from plcsim.check.operating import (
    FAULTS,
    OperatingCondition,
    assumes,
    fault_problems,
    parts_at_once,
    undeclared_breaks,
)
from plcsim.check.quantities import Quantity, count, durations, duty, event_data, final, measure, spacing, value_at
from plcsim.check.static import StaticCheck, program_uses_no
from plcsim.check.temporal import Always, Eventually, Holds, HoldsBuilder, Never, always, eventually, holds, never
from plcsim.trace.facade import Trace


def evaluate_all(checks: Iterable[Check], trace: Trace, analysis: Any = None) -> list[tuple[Check, Verdict]]:
    """Evaluate checks on one trace; an error in a check becomes a failed verdict, never a crash."""
    ctx = Context.of(trace, analysis)
    out = []
    for check in checks:
        try:
            verdict = check.evaluate(ctx)
            verdict.signals += [s for s in check.extra_signals if s not in verdict.signals]
        except Exception as exc:  # noqa: BLE001 - a check's own bug is reported, not raised
            verdict = Verdict(False, f"the check could not be evaluated: {type(exc).__name__}: {exc}")
        out.append((check, verdict))
    return out


__all__ = [
    "Span",
    "Context",
    "Verdict",
    "Check",
    "Condition",
    "Occurrences",
    "Quantity",
    "StaticCheck",
    "on",
    "off",
    "value",
    "all_of",
    "any_of",
    "not_",
    "implies",
    "same",
    "as_condition",
    "rises",
    "falls",
    "becomes",
    "event",
    "action",
    "calls",
    "either",
    "seen",
    "seen_at",
    "never",
    "always",
    "holds",
    "eventually",
    "count",
    "spacing",
    "durations",
    "duty",
    "final",
    "value_at",
    "measure",
    "event_data",
    "program_uses_no",
    "assumes",
    "parts_at_once",
    "undeclared_breaks",
    "fault_problems",
    "OperatingCondition",
    "FAULTS",
    "evaluate_all",
    "AllOf",
    "AnyOf",
    "Compare",
    "Not",
    "On",
    "Value",
    "Becomes",
    "Calls",
    "Edge",
    "Either",
    "EventOccurrences",
    "Response",
    "ResponseBuilder",
    "Seen",
    "Always",
    "Eventually",
    "Holds",
    "HoldsBuilder",
    "Never",
]
