"""CPU profiles: what one controller family names and numbers, as one description each.

A profile says what a student's program may address and what makes its tasks run: the memory areas
and their address grammar, the system bits the controller keeps, the restart kinds, the task triggers
and the instruction set. Two are registered (entry-point group ``plcsim.profiles``,
:mod:`plcsim.core.registry`): ``s7-1200`` (:mod:`plcsim.controllers.s7.profile`) and ``tecomat-ns950``
(:mod:`plcsim.controllers.tecomat.profile`); a front end names the one its programs are written for
(:func:`plcsim.frontends.frontend_for`), and ``plcsim list --profiles`` shows them.

>>> s7 = profile("S7-1200")
>>> s7.family, [a.name for a in s7.areas], s7.parse_address("%MW10").bits
('Siemens S7-1200', ['I', 'Q', 'M', 'DB'], 16)
>>> [t.tasks for t in s7.triggers], "TON" in s7.instructions()
(['OB1', 'OB30..OB38', 'OB100'], True)
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

from plcsim.core import registry
from plcsim.core.errors import ConfigurationError, did_you_mean


@dataclass(frozen=True)
class MemoryArea:
    """A memory area a program addresses: its letter, what it holds, an example of each width."""

    name: str
    holds: str
    examples: tuple[str, ...]


@dataclass(frozen=True)
class SystemBit:
    """A bit or register the controller itself keeps up to date, and what it means."""

    name: str
    where: str
    meaning: str


@dataclass(frozen=True)
class Restart:
    """A way from STOP to RUN and what survives it."""

    name: str
    keeps: str


@dataclass(frozen=True)
class Trigger:
    """What makes a task run: its kind, the tasks of that kind (``OB30..OB38``), and how they are due."""

    kind: str
    """``cyclic``, ``interrupt`` (periodic with a phase), ``startup``, ``event``, ``first cycle``, ..."""
    tasks: str
    meaning: str
    first: int
    last: int
    priority: int = 1
    """The default priority of its tasks (higher pre-empts lower)."""

    def covers(self, number: int) -> bool:
        """Whether the task numbered ``number`` is one of this trigger's."""
        return self.first <= number <= self.last


@dataclass(frozen=True)
class Profile:
    """One controller family as its programs see it (the design's "CPU profile").

    ``parse_address`` is the address grammar (an error names the syntax); ``instructions`` lists the
    instruction set, computed when asked (the Tecomat's comes from its manual's tables)."""

    name: str
    family: str
    byte_order: str
    """``big`` (S7: %MW10 is %MB10 high, %MB11 low) or ``little`` (Tecomat: RW4 is R4 low, R5 high)."""
    areas: tuple[MemoryArea, ...]
    parse_address: Callable[[str], Any]
    system_bits: tuple[SystemBit, ...]
    restarts: tuple[Restart, ...]
    triggers: tuple[Trigger, ...]
    instructions: Callable[[], frozenset[str]]
    controller: str
    """Where its controller lives (``plcsim.controllers.s7.cpu:CPU``): the runtime that schedules its tasks."""
    source_reader: str = ""
    """Where the reader of program text in its default language lives
    (``plcsim.frontends.python.program:Program.from_source``), for a controller given text instead of a
    read program; found by name when called, so that no controller imports a front end. Empty: none."""

    def trigger_of(self, number: int) -> Trigger | None:
        """The trigger of the task numbered ``number``, or None if the family has no such task."""
        return next((t for t in self.triggers if t.covers(number)), None)


def names() -> list[str]:
    """The registered profiles' names (``s7-1200``, ``tecomat-ns950``), without importing them."""
    return [ep.name for ep in registry.entry_points(registry.PROFILES)]


def profile(name: str) -> Profile:
    """The registered profile ``name`` (any case)."""
    for ep in registry.entry_points(registry.PROFILES):
        if ep.name.lower() == name.lower():
            found = registry.load(ep)
            if not isinstance(found, Profile):
                raise ConfigurationError(
                    f"the {registry.PROFILES} entry point {ep.name} = {ep.value!r} names a "
                    f"{type(found).__name__}, not a plcsim.controllers.profiles.Profile"
                )
            return found
    known = names()
    raise ConfigurationError(f"no CPU profile {name!r}{did_you_mean(name, known)} (profiles: {', '.join(known)})")


def all_profiles() -> list[Profile]:
    """Every registered profile, in name order."""
    return [profile(name) for name in names()]


__all__ = ["MemoryArea", "Profile", "Restart", "SystemBit", "Trigger", "all_profiles", "names", "profile"]
