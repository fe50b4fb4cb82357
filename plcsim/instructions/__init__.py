"""The textbook's instructions: timers, counters, edges, math, conversion, MOVE, RD_LOC_T, jumps.

Function-block instance types are declared in a program (``TON_A = IEC_TIMER()``) and called as
``t.TON_A.TON(IN=..., PT="10s")``; the other instructions are functions (``P``, ``DIV``, ``MOVE``).
"""

from __future__ import annotations

from typing import Any

from plcsim.clock import Clock
from plcsim.instructions.arithmetic import MATH_FUNCTIONS
from plcsim.instructions.counters import IecCounter
from plcsim.instructions.edges import EdgeTrigger
from plcsim.instructions.system import JMP, RET
from plcsim.instructions.timers import PT, RT, IecTimer, TimerDialect
from plcsim.tags import FBType
from plcsim.types import ElementaryType, Int


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

FB_TYPES = {fb.name: fb for fb in (IEC_TIMER, IEC_COUNTER, R_TRIG, F_TRIG)}

FB_BOXES = {
    "IEC_TIMER": {"TON", "TOF", "TP", "TONR"},
    "IEC_COUNTER": {"CTU", "CTD", "CTUD"},
    "R_TRIG": {"R_TRIG"},
    "F_TRIG": {"F_TRIG"},
}
"""Box methods each instance type offers; every box returns a Bool (its Q / QU)."""

FB_MEMBERS: dict[str, dict[str, str]] = {
    "IEC_TIMER": {"Q": "Bool", "ET": "Time", "PT": "Time", "IN": "Bool"},
    "IEC_COUNTER": {
        "CV": "value",
        "PV": "value",
        "QU": "Bool",
        "QD": "Bool",
        "Q": "Bool",
        "CU": "Bool",
        "CD": "Bool",
        "R": "Bool",
        "LD": "Bool",
    },
    "R_TRIG": {"Q": "Bool", "CLK": "Bool", "Stat_Bit": "Bool"},
    "F_TRIG": {"Q": "Bool", "CLK": "Bool", "Stat_Bit": "Bool"},
}
"""Members a program may read; ``value`` means the counter's count type."""

FB_WRITABLE: dict[str, set[str]] = {"IEC_TIMER": {"PT"}, "IEC_COUNTER": {"CV", "PV"}, "R_TRIG": set(), "F_TRIG": set()}
"""Members a program may write directly (the rest are outputs the box computes)."""

PURE_INSTRUCTIONS: dict[str, Any] = {**MATH_FUNCTIONS, "RT": RT, "PT": PT, "JMP": JMP, "RET": RET}
"""Instructions that need no CPU: they are the same for every program."""

BOOL_RESULTS = {"P", "N", "P_TRIG", "N_TRIG", "P_COIL", "N_COIL", "IN_RANGE", "OUT_RANGE"}
"""Instruction functions whose result is a Bool (used by the compiler's static typing)."""

CPU_BOUND = {"P", "N", "P_TRIG", "N_TRIG", "P_COIL", "N_COIL", "MOVE", "RD_LOC_T"}
"""Instructions built per CPU (they read or write its memory or clock)."""

__all__ = [
    "IEC_TIMER",
    "IEC_COUNTER",
    "R_TRIG",
    "F_TRIG",
    "IecTimer",
    "IecCounter",
    "EdgeTrigger",
    "TimerDialect",
    "RT",
    "PT",
    "JMP",
    "RET",
]
