"""What a front end hands the runtime: a loaded program, whatever language its source was in.

``source file --front end--> LoadedProgram --runtime--> trace``. The runtime never sees source text:
it runs the networks' callables, numbers the trace's rows by the tasks' numbers, partitions the process
image by the tags each task uses, and names a fault's place by the network's source span. A front end
never reaches into the runtime: it receives a :class:`LinkTarget` (the tag table, the runtime's bound
instructions and hooks, the configuration) and returns a :class:`LoadedProgram`. The hooks carry the
runtime's names (:class:`RuntimeHooks`); a front end binds them to whatever names its code calls.
"""

from __future__ import annotations

import re
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import Any, Protocol

from plcsim.controllers.s7.config import CPUConfig
from plcsim.tags.table import TagTable

_MERGED_LOCAL = re.compile(r"\b_n\d+_([A-Za-z_]\w*)")


def merged_local(network: int, name: str) -> str:
    """The name the local ``name`` of a task's ``network``-th network takes in the task's merged function (two
    networks may name a local alike); :func:`student_names` undoes it in a message."""
    return f"_n{network}_{name}"


def student_names(message: str) -> str:
    """``message`` with the merged function's locals named as the program wrote them (``'_n1_s'`` -> ``'s'``).

    >>> student_names("cannot access local variable '_n1_s' where it is not associated with a value")
    "cannot access local variable 's' where it is not associated with a value"
    """
    return _MERGED_LOCAL.sub(r"\1", message)


@dataclass(frozen=True)
class NetworkSpec:
    """One network: its name, title, jump label and first source line."""

    name: str
    title: str
    label: str | None
    lineno: int


@dataclass
class TaskSpec:
    """One task: trigger kind (``cyclic``, ``interrupt``, ``startup``), networks, timing and trace number."""

    name: str
    kind: str
    networks: list[NetworkSpec]
    period_ns: int | None = None
    """None: the program gives none (the CPU takes the hardware configuration's, or the default)."""
    phase_ns: int = 0
    priority: int = 1
    duration_ns: int | None = None
    number: int = 0
    """The task's number in the trace's task column (the OB number on an S7)."""


@dataclass(frozen=True)
class LoadedNetwork:
    """A network ready to run: ``run(t)`` and the lines it spans in the student's file."""

    run: Callable[[Any], None]
    span: tuple[int, int]


@dataclass
class LoadedTask:
    """A task ready to run: its spec, its networks, optionally one callable running all of them in
    order (a fast path a front end may plan once per download), and the tags its networks use."""

    spec: TaskSpec
    networks: list[LoadedNetwork]
    whole: Callable[[Any], None] | None = None
    tags_used: frozenset[str] = frozenset()


@dataclass
class ProgramFacts:
    """Neutral static facts: what the program reads, writes and calls (for the trace and the checks)."""

    tags_read: frozenset[str] = frozenset()
    tags_written: frozenset[str] = frozenset()
    instructions: frozenset[str] = frozenset()


@dataclass
class LoadedProgram:
    """A program linked against one CPU's tags: tasks with callables, facts and the front end's notes."""

    filename: str
    tasks: list[LoadedTask]
    facts: ProgramFacts = field(default_factory=ProgramFacts)
    warnings: list[str] = field(default_factory=list)
    inert_timers: set[str] = field(default_factory=set)
    """Paths of timer instances that must not start (the S7 rule for a timer whose Q and ET go unread)."""
    compiled: Any = None
    """The front end's own compiled form (the Python front end's CompiledProgram: its analysis feeds the
    static checks); None for a front end without one."""


@dataclass(frozen=True)
class RuntimeHooks:
    """The runtime's checks a program's code calls while it runs, bound to one CPU."""

    tick: Callable[[], None]
    """The cycle watchdog: called once per loop pass; raises when one execution loops past the budget."""
    tags_of: Callable[[Any], dict[str, Any]]
    """The tags guard: ``tags_of(t)`` is the tags' member dict, after checking that ``t`` is this CPU's tags."""
    store: Callable[[Any, str, Any], None]
    """``store(container, name, value)``: a store into a tag or a data-block member, converted to its type."""
    store_member: Callable[[Any, str, Any], None]
    """``store_member(instance, name, value)``: a store into a writable member of an instance (a timer's PT)."""


@dataclass(frozen=True)
class LinkTarget:
    """What a front end may know of the CPU it links against."""

    table: TagTable
    aliased: frozenset[str]
    config: CPUConfig
    instructions: Mapping[str, Any]
    """The instructions that need this CPU (the edge instructions, MOVE, RD_LOC_T), by instruction name."""
    hooks: RuntimeHooks
    """The watchdog tick and the store guards, for the code a front end generates."""


class SourceProgram(Protocol):
    """A program as a front end read it: it declares tags and links into a :class:`LoadedProgram`."""

    @property
    def filename(self) -> str: ...

    def declare_into(self, table: TagTable) -> TagTable:
        """A copy of ``table`` with the program's own declarations added."""
        ...

    def absolute_addresses(self) -> list[str]:
        """The absolute addresses (``"%M10.0"``) the program uses without declaring them."""
        ...

    def link(self, target: LinkTarget) -> LoadedProgram:
        """Compile against the CPU's table and instructions."""
        ...
