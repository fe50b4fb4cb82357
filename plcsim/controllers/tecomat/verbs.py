"""Scenario verbs the Tecomat controller brings: raising an interrupt source (P41..P48) and setting the
real-time clock (S5..S12).

They are :class:`~plcsim.plant.verbs.RigVerb` s with ``controller=True``: the Tecomat lists them in its
``VERBS``, and a scenario that uses one on another controller (an S7 program) is refused before the run
starts, naming the line (:func:`plcsim.scenario.names.controller_verb_problems`).

>>> interrupt(1, t="2s").describe(), set_clock("07:59:30", t="1s").describe()
('raise interrupt source 1 (P41) at 2 s', 'set the real-time clock to 07:59:30 at 1 s')
>>> set_clock("7.59", t="1s")
Traceback (most recent call last):
...
plcsim.scenario.verbs.ScenarioError: ...: set_clock('7.59'): write the time of day as 'HH:MM:SS'
"""

from __future__ import annotations

import datetime as _dt
from typing import Any

from plcsim.core.errors import defined_at
from plcsim.plant.verbs import RigVerb
from plcsim.scenario.verbs import Action, ScenarioError, Trigger

SOURCES = tuple(str(k) for k in range(1, 9))
"""The interrupt sources 1..8 (manual Fig. 5: P41..P48)."""

INTERRUPT = RigVerb(
    "interrupt",
    "interrupt",
    "interrupt source",
    "raise interrupt source {target} (P4{target})",
    targets="interrupt_sources",
    doc="a verb of the Tecomat NS950 controller (.il programs): source 1..8 runs P41..P48 at the next turnaround",
    controller=True,
)
SET_CLOCK = RigVerb(
    "set_clock",
    "set_time_of_day",
    "time of day",
    "set the real-time clock to {target}",
    doc="a verb of the Tecomat NS950 controller (.il programs): the clock S5..S12 runs on from the time set",
    controller=True,
)
VERBS = {v.name: v for v in (INTERRUPT, SET_CLOCK)}


def interrupt(source: int, t: Any = None, *, when: Trigger | None = None, delay: Any = 0) -> Action:
    """Raise interrupt source ``source`` (1..8): P(40 + source) runs at the next turnaround if the program
    enabled it (bit S29.(source - 1), setting ``event_enable_byte``)."""
    if str(source) not in SOURCES:
        raise ScenarioError(f"{defined_at()}: interrupt({source!r}): the sources are 1..8 (P41..P48)")
    return INTERRUPT(str(source), t, when=when, delay=delay)


def set_clock(time_of_day: str, t: Any = None, *, when: Trigger | None = None, delay: Any = 0) -> Action:
    """Set the real-time clock to ``"HH:MM:SS"`` of the same day, as a technician does at the panel."""
    try:
        _dt.time.fromisoformat(time_of_day)
    except (TypeError, ValueError):
        raise ScenarioError(
            f"{defined_at()}: set_clock({time_of_day!r}): write the time of day as 'HH:MM:SS'"
        ) from None
    return SET_CLOCK(time_of_day, t, when=when, delay=delay)
