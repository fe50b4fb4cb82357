"""The textbook's instructions: timers, counters, edges, math, conversion, MOVE, RD_LOC_T, jumps, and
the PLC836 step mechanisms (seed 003).

Function-block instance types are declared in a program (``TON_A = IEC_TIMER()``) and called as
``t.TON_A.TON(IN=..., PT="10s")``; the other instructions are functions (``P``, ``DIV``, ``MOVE``).
"""

from __future__ import annotations

import datetime as _dt
import difflib
import functools
import inspect
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any, Protocol

from plcsim.controllers.s7.instructions.arithmetic import MATH_FUNCTIONS
from plcsim.controllers.s7.instructions.counters import IecCounter
from plcsim.controllers.s7.instructions.edges import EDGE_INSTRUCTIONS, EDGE_OPERANDS, EdgeTrigger, bind_edge
from plcsim.controllers.s7.instructions.mechanisms import PLC836, Mechanism
from plcsim.controllers.s7.instructions.system import JMP, RET, make_move, make_rd_loc_t
from plcsim.controllers.s7.instructions.timers import PT, RT, IecTimer, TimerDialect
from plcsim.core.clock import Clock
from plcsim.tags.table import FBType
from plcsim.tags.types import ElementaryType, Int


def _timer(context: Any, start: Any, path: str) -> IecTimer:
    clock = context.clock if context is not None else Clock()
    live = context.timer_dialect == TimerDialect.S7_1200 if context is not None else True
    return IecTimer(clock, path, live=live)


def _counter(context: Any, start: Any, path: str) -> IecCounter:
    value_type = start if isinstance(start, ElementaryType) else Int
    saturate = context.counter_overflow == "saturate" if context is not None else False
    return IecCounter(value_type, saturate=saturate, path=path)


IEC_TIMER = FBType(
    "IEC_TIMER", _timer, retain=False, doc="Timer instance (members PT, ET, IN, Q); boxes TON, TOF, TP, TONR."
)
IEC_COUNTER = FBType(
    "IEC_COUNTER",
    _counter,
    retain=True,
    doc="Counter instance (CU, CD, R, LD, QU, QD, PV, CV), retentive; boxes CTU, CTD, CTUD.",
)


def _mechanism(context: Any, start: Any, path: str) -> Mechanism:
    clock = context.clock if context is not None else Clock()
    mode = getattr(getattr(context, "config", None), "mechanism_mode", PLC836)
    return Mechanism(clock, path, mode=mode)


MECHANISM = FBType(
    "MECHANISM",
    _mechanism,
    retain=False,
    doc="PLC836 step mechanism (members ACTIVE, STEP, ET, ERR, LINE); boxes begin, step, wait_until, "
    "wait_while, delay, ex, bex, error, goto, end, init, start.",
)
R_TRIG = FBType(
    "R_TRIG",
    lambda context, start, path: EdgeTrigger(path),
    retain=False,
    doc="Rising-edge function block (CLK, Q, Stat_Bit).",
)
F_TRIG = FBType(
    "F_TRIG",
    lambda context, start, path: EdgeTrigger(path),
    retain=False,
    doc="Falling-edge function block (CLK, Q, Stat_Bit).",
)


def box_hint(name: str) -> str:
    """Where the box a mistyped name is near lives (``TONN`` -> TON of an IEC_TIMER instance), as the end of
    an error message; empty if no box is near.

    >>> box_hint("TONN")
    '; TON is a box of an IEC_TIMER instance: declare TIMER = IEC_TIMER() and call t.TIMER.TON(IN=..., PT=...)'
    >>> box_hint("LED")
    ''
    """
    boxes = {box: block for block in BLOCKS.values() for box in block.boxes}
    near = difflib.get_close_matches(name.upper(), boxes, n=1, cutoff=0.75)
    if not near:
        return ""
    box, block = near[0], boxes[near[0]]
    params = [p for p in inspect.signature(getattr(block.instance, box)).parameters if p != "self"]
    example = {"IEC_TIMER": "TIMER", "IEC_COUNTER": "COUNTER", "MECHANISM": "MECH"}.get(block.name, "EDGE")
    call = ", ".join(f"{p}=..." for p in params)
    return (
        f"; {box} is a box of an {block.name} instance: declare {example} = {block.name}() and call "
        f"t.{example}.{box}({call})"
    )


@dataclass(frozen=True)
class BlockMember:
    """A member of an instance: its type (``Bool``, ``Time``, or ``value``, the counter's count type),
    whether a program may assign it, and whether the trace records it by default."""

    name: str
    type: str
    writable: bool = False
    traced: bool = False


@dataclass(frozen=True)
class Block:
    """Everything plcsim knows about one instance type (IEC_TIMER ...), read by the compiler's typing, the
    host access, the recorder and the student reference: no parallel tables.

    >>> timer = BLOCKS["IEC_TIMER"]
    >>> timer.boxes, timer.readable["ET"], sorted(timer.writable), timer.traced
    (('TON', 'TOF', 'TP', 'TONR'), 'Time', ['PT'], ('Q', 'ET'))
    """

    fb: FBType
    instance: type
    """The class of the instances; it reads a member as last computed with ``trace_source`` (no refresh)."""
    boxes: tuple[str, ...]
    """Its box methods; every box returns a Bool (its Q / QU)."""
    members: tuple[BlockMember, ...]
    trace_kind: str
    """The trace's kind column for its members (``timer``, ``counter``, ``memory``)."""

    @property
    def name(self) -> str:
        return self.fb.name

    @property
    def readable(self) -> dict[str, str]:
        """Member name -> type, for every member a program may read, in the manual's order."""
        return {m.name: m.type for m in self.members}

    @functools.cached_property
    def writable(self) -> frozenset[str]:
        """Members a program may write directly (the rest are outputs the box computes); computed once, as
        every store into an instance member asks it."""
        return frozenset(m.name for m in self.members if m.writable)

    @property
    def traced(self) -> tuple[str, ...]:
        """Members the trace records when no signals are chosen."""
        return tuple(m.name for m in self.members if m.traced)

    def member(self, name: str) -> BlockMember | None:
        return next((m for m in self.members if m.name == name), None)

    def trace_type(self, name: str) -> str:
        """The trace column type of a member: ``bool`` or ``int`` (TIME in ms, counts)."""
        member = self.member(name)
        return "bool" if member is not None and member.type == "Bool" else "int"


def _members(*specs: str, writable: tuple[str, ...] = (), traced: tuple[str, ...] = ()) -> tuple[BlockMember, ...]:
    return tuple(
        BlockMember(name, kind, name in writable, name in traced) for name, kind in (spec.split(":") for spec in specs)
    )


_EDGE_MEMBERS = _members("Q:Bool", "CLK:Bool", "Stat_Bit:Bool", traced=("Q",))
BLOCKS: dict[str, Block] = {
    block.name: block
    for block in (
        Block(
            IEC_TIMER,
            IecTimer,
            ("TON", "TOF", "TP", "TONR"),
            _members("Q:Bool", "ET:Time", "PT:Time", "IN:Bool", writable=("PT",), traced=("Q", "ET")),
            "timer",
        ),
        Block(
            IEC_COUNTER,
            IecCounter,
            ("CTU", "CTD", "CTUD"),
            _members(
                "CV:value",
                "PV:value",
                "QU:Bool",
                "QD:Bool",
                "Q:Bool",
                "CU:Bool",
                "CD:Bool",
                "R:Bool",
                "LD:Bool",
                writable=("CV", "PV"),
                traced=("CV", "QU", "QD"),
            ),
            "counter",
        ),
        Block(R_TRIG, EdgeTrigger, ("R_TRIG",), _EDGE_MEMBERS, "memory"),
        Block(F_TRIG, EdgeTrigger, ("F_TRIG",), _EDGE_MEMBERS, "memory"),
        Block(
            MECHANISM,
            Mechanism,
            (
                "begin",
                "step",
                "wait_until",
                "wait_while",
                "delay",
                "ex",
                "bex",
                "error",
                "goto",
                "end",
                "init",
                "start",
            ),
            _members(
                "ACTIVE:Bool",
                "STEP:Int",
                "ET:Time",
                "ERR:Int",
                "LINE:Int",
                writable=("ACTIVE",),
                traced=("ACTIVE", "STEP", "ET", "ERR"),
            ),
            "memory",
        ),
    )
}
"""The instance types by name."""

FB_TYPES = {name: block.fb for name, block in BLOCKS.items()}
"""The declaration of each instance type (``TON_A = IEC_TIMER()``), from :data:`BLOCKS`."""

_BY_CLASS = {block.instance: block for block in reversed(BLOCKS.values())}


def block_of(value: Any) -> Block | None:
    """The description of an instance's type, or None if ``value`` is no instance (R_TRIG and F_TRIG
    share one class and the same members: an edge instance is described as an R_TRIG)."""
    return _BY_CLASS.get(type(value))


def block_named(name: str) -> Block | None:
    """The description of the instance type ``name`` (``"IEC_TIMER"``), or None."""
    return BLOCKS.get(name)


class Host(Protocol):
    """What an instruction that needs the CPU is bound to: the S7 CPU is one (a test's stand-in another)."""

    t: Any
    """The tags, as the networks see them."""

    def resolve_path(self, path: str) -> tuple[Any, Any]:
        """Where ``"NAME"``, ``"DB.member"`` or ``"%M2.0"`` lives: (container, key)."""
        ...

    def local_time(self) -> tuple[_dt.datetime, int]:
        """The CPU's local date and time now, and its nanoseconds."""
        ...


@dataclass(frozen=True)
class Function:
    """One instruction a network calls as a function (``P``, ``DIV``, ``MOVE`` ...).

    ``run`` is its implementation when it is the same for every program; an instruction that reads or
    writes a CPU's memory or clock has ``bind`` instead, and each CPU calls ``bind(cpu)`` for its own
    implementation (the CPU binds every such description alike and names none of them)."""

    name: str
    run: Callable[..., Any] | None = None
    returns_bool: bool = False
    """Its result is a Bool (the compiler's static typing: storing it into a BOOL needs no check)."""
    bind: Callable[[Host], Callable[..., Any]] | None = None
    named: tuple[int, ...] = ()
    """Positions of the arguments that name a memory bit rather than pass its value (the edge memory of
    ``P(t.S1, t.SB1)``): the compiler passes the tag's name there."""

    @property
    def needs_cpu(self) -> bool:
        """Whether each CPU builds its own implementation (with :attr:`bind`)."""
        return self.bind is not None


def _functions() -> dict[str, Function]:
    boolean = {"IN_RANGE", "OUT_RANGE"}
    pure = {**MATH_FUNCTIONS, "RT": RT, "PT": PT, "JMP": JMP, "RET": RET}
    found = {name: Function(name, run, returns_bool=name in boolean) for name, run in pure.items()}
    for name in EDGE_INSTRUCTIONS:
        found[name] = Function(name, returns_bool=True, bind=bind_edge(name), named=EDGE_OPERANDS[name])
    found["MOVE"] = Function("MOVE", bind=lambda host: make_move(host.resolve_path))
    found["RD_LOC_T"] = Function("RD_LOC_T", bind=lambda host: make_rd_loc_t(host.local_time))
    return found


def bind_instructions(host: Host) -> dict[str, Callable[..., Any]]:
    """The instructions that need a CPU, each built for ``host`` from its description (name -> callable)."""
    return {f.name: f.bind(host) for f in FUNCTIONS.values() if f.bind is not None}


FUNCTIONS: dict[str, Function] = _functions()
"""The instructions of networks by name."""

PURE_INSTRUCTIONS: dict[str, Any] = {f.name: f.run for f in FUNCTIONS.values() if not f.needs_cpu}
"""Instructions that need no CPU, name -> implementation (from :data:`FUNCTIONS`)."""

BOOL_RESULTS = frozenset(f.name for f in FUNCTIONS.values() if f.returns_bool)
"""Instruction functions whose result is a Bool (from :data:`FUNCTIONS`)."""

CPU_BOUND = frozenset(f.name for f in FUNCTIONS.values() if f.needs_cpu)
"""Instructions built per CPU (from :data:`FUNCTIONS`)."""

__all__ = [
    "BLOCKS",
    "FUNCTIONS",
    "Block",
    "Function",
    "Host",
    "bind_instructions",
    "BlockMember",
    "block_named",
    "box_hint",
    "block_of",
    "IEC_TIMER",
    "IEC_COUNTER",
    "R_TRIG",
    "F_TRIG",
    "MECHANISM",
    "Mechanism",
    "IecTimer",
    "IecCounter",
    "EdgeTrigger",
    "TimerDialect",
    "RT",
    "PT",
    "JMP",
    "RET",
]
