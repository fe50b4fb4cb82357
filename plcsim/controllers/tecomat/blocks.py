"""Function blocks on register pairs RW0..RW254: counters, shift registers, timers (manual §7.5).

Inputs come from stack levels (a binary input is the OR of its level), outputs go back into them. Each
block is a *core*, a function from its input levels to its output levels, and a :class:`Shape` saying
which levels those are; the plain path wraps the core into a closure working on the stack, the fused
path (:mod:`plcsim.controllers.tecomat.fused`) writes the same statements out in its generated code, on
the levels and registers it holds in locals (the two are compared on random programs). The
word is read from R at every execution, so ordinary instructions may change it (EX-16 clears a counter
with ``res low citac``). Each block also keeps hidden state, keyed by its kind and word (G39): the edge
memories ("dynamic control variables") and a timer's phase. A cold restart initialises them as the
manual's H7 describes: the word cleared and the dynamic variables *set*, so a control input already at 1
when a block first runs is not a rising edge (TOF's falling edge likewise needs a 1 seen first).

Choices (G33, G38, G40, G41): carries UPC/DOWNC and DATAO are masks valid for the execution that made
them, else 0; RESET dominates an edge and the edge memory is updated during reset; a timer counts past
its preset up to ``timer_max`` units (S0.4 for the activation, S0.5 for the cycle it got there);
RTO's YT = content >= preset also while waiting, YC = the overflow mask. Time: a timer adds the units of
the interval between the previous turnaround and this one, only if it ran (and was timing) in the
previous cycle too ("otherwise its time stops"); ``per_timer`` keeps each timer's remainder from its
start, ``global`` counts the ticks of the time base.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from plcsim.controllers.tecomat.assembly import Instruction
from plcsim.controllers.tecomat.settings import TIME_BASES_NS

if TYPE_CHECKING:
    from plcsim.controllers.tecomat.machine import Machine

FFFF = 0xFFFF
Code = Callable[[], int]
Core = Callable[..., Any]


@dataclass(frozen=True)
class Shape:
    """Where a block's core finds its inputs and puts its outputs on the stack.

    The core is called with the levels ``A(inputs-1) .. A0`` (the deepest first; a binary input may be any
    truth value); with ``push`` its first output is pushed, and its outputs then go to the levels
    ``places`` (counted after the push). A core with one output returns it, one with more a tuple."""

    inputs: int
    push: bool
    places: tuple[int, ...]
    preset: bool = False
    """The last input (A0) is a number (a timer's preset); the others are binary."""


class BlockState:
    """The hidden state of one block: edge memories, timing phase, remainder, overflow."""

    __slots__ = ("index", "kind", "prev", "prev2", "timing", "acc", "last_pass", "overflow", "initial")

    def __init__(self, kind: str, index: int, initial: bool):
        self.kind, self.index, self.initial = kind, index, initial
        self.reset()

    def reset(self) -> None:
        self.prev = self.prev2 = self.initial
        self.timing = False
        self.acc = 0
        self.last_pass = -10
        self.overflow = False


def _state(m: Machine, kind: str, index: int, initial: bool = True) -> BlockState:
    for block in m.blocks:
        if block.kind == kind and block.index == index:
            return block
    block = BlockState(kind, index, initial)
    m.blocks.append(block)
    return block


def state_of(m: Machine, instr: Instruction) -> BlockState:
    """The hidden state of the block of ``instr`` (the one its core works on)."""
    return _state(m, instr.mnemonic, _word(m, instr)[1], instr.mnemonic != "TOF")


def _word(m: Machine, instr: Instruction) -> tuple[bytearray, int]:
    op = instr.arg.word if hasattr(instr.arg, "word") else instr.arg
    return m.pad.areas["R"], op.index


# -- counters -----------------------------------------------------------------------------------------


def _ctu_ctd(m: Machine, instr: Instruction) -> Core:
    up = instr.mnemonic == "CTU"
    data, i = _word(m, instr)
    flags = m.pad.areas["S"]
    st = _state(m, instr.mnemonic, i)
    preset = m.config.ctd_set_value

    def counter(count: int, clear: int) -> tuple[int, int]:  # A1 count, A0 reset/set -> A2 carry, A0 value
        count = count != 0
        edge = count and not st.prev
        st.prev = count
        value = data[i] | data[i + 1] << 8
        carry = 0
        if clear:
            value = 0 if up else preset
        elif edge:
            value += 1 if up else -1
            if not 0 <= value <= FFFF:
                value &= FFFF
                carry = FFFF
        data[i], data[i + 1] = value & 0xFF, value >> 8
        flags[0] = (5 if value == 0 else 0) | (6 if carry else 0)  # S0.0 zero, S0.1 carry, S0.2 either
        return value, carry

    return counter


def _cnt(m: Machine, instr: Instruction) -> Core:
    data, i = _word(m, instr)
    flags = m.pad.areas["S"]
    st = _state(m, "CNT", i)

    def cnt(up: int, down: int, clear: int) -> tuple[int, int, int]:  # -> A3 UPC, A2 DOWNC, A0 VAL
        up, down = up != 0, down != 0
        rise_up, rise_down = up and not st.prev, down and not st.prev2
        st.prev, st.prev2 = up, down
        value = data[i] | data[i + 1] << 8
        upc = downc = 0
        if clear:
            value = 0
        elif rise_up and not rise_down:
            value += 1
            if value > FFFF:
                value, upc = 0, FFFF
        elif rise_down and not rise_up:
            value -= 1
            if value < 0:
                value, downc = FFFF, FFFF
        data[i], data[i + 1] = value & 0xFF, value >> 8
        flags[0] = (5 if value == 0 else 0) | (6 if upc | downc else 0)
        return value, upc, downc

    return cnt


# -- shift registers ----------------------------------------------------------------------------------


def _shift(m: Machine, instr: Instruction) -> Core:
    left = instr.mnemonic == "SFL"
    data, i = _word(m, instr)
    st = _state(m, instr.mnemonic, i)

    def shift(clock: int, serial: int) -> tuple[int, int]:  # A1 CLK, A0 DATAI -> A1 DATAO, A0 VAL
        clock = clock != 0
        edge = clock and not st.prev
        st.prev = clock
        value = data[i] | data[i + 1] << 8
        out = 0
        if edge:
            bit = 1 if serial else 0
            if left:
                out = FFFF if value & 0x8000 else 0
                value = value << 1 & FFFF | bit
            else:
                out = FFFF if value & 1 else 0
                value = value >> 1 | bit << 15
            data[i], data[i + 1] = value & 0xFF, value >> 8
        return value, out

    return shift


# -- timers -------------------------------------------------------------------------------------------


def _clock(m: Machine, st: BlockState, unit: int) -> Callable[[bool], int]:
    """Whole time units to add in this execution (0 unless the timer ran and timed in the last cycle
    and, with ``count``, times in this one: a waiting RTO keeps its remainder)."""
    per_timer = m.config.timer_ticks == "per_timer"

    def units(count: bool = True) -> int:
        ran_last = st.last_pass == m.pass_no - 1
        st.last_pass = m.pass_no
        if not (count and st.timing and ran_last):
            return 0
        if per_timer:
            acc = st.acc + m.t0 - m.prev_t0
            st.acc = acc % unit
            return acc // unit
        return m.t0 // unit - m.prev_t0 // unit

    return units


def _timer_parts(
    m: Machine, instr: Instruction
) -> tuple[bytearray, int, bytearray, BlockState, Callable[[bool], int], int]:
    data, i = _word(m, instr)
    initial = instr.mnemonic != "TOF"
    st = _state(m, instr.mnemonic, i, initial)
    return data, i, m.pad.areas["S"], st, _clock(m, st, TIME_BASES_NS[instr.arg.code]), m.config.timer_max


def _advance(data: bytearray, i: int, st: BlockState, units: int, top: int) -> tuple[int, bool]:
    """The word plus ``units``, held at ``top``; whether it reached ``top`` in this execution."""
    value = data[i] | data[i + 1] << 8
    now_over = False
    if units:
        value += units
        if value >= top:
            value = top
            now_over = not st.overflow
            st.overflow = True
        data[i], data[i + 1] = value & 0xFF, value >> 8
    return value, now_over


def _timer_flags(flags: bytearray, preset: int, value: int, st: BlockState, now_over: bool) -> None:
    flags[0] = (preset == value) | (preset < value) << 1 | (preset <= value) << 2 | st.overflow << 4 | now_over << 5


def _clear(data: bytearray, i: int, st: BlockState, flags: bytearray) -> None:
    data[i] = data[i + 1] = 0
    st.acc = 0
    st.overflow = False
    flags[0] = 0


def _ton(m: Machine, instr: Instruction) -> Core:
    data, i, flags, st, units, top = _timer_parts(m, instr)

    def ton(xt: int, preset: int) -> int:  # A1 XT, A0 preset -> A0 YT
        if not xt:  # what units() would add is cleared with the rest
            st.last_pass = m.pass_no
            st.timing = False
            _clear(data, i, st, flags)
            return 0
        passed = units()
        if not st.timing:  # the rising edge: timing starts at this turnaround
            _clear(data, i, st, flags)
            st.timing = True
            passed = 0
        value, now_over = _advance(data, i, st, passed, top)
        _timer_flags(flags, preset, value, st, now_over)
        return FFFF if value >= preset else 0

    return ton


def _tof(m: Machine, instr: Instruction) -> Core:
    data, i, flags, st, units, top = _timer_parts(m, instr)

    def tof(xt: int, preset: int) -> int:  # active while XT = 0, from its falling edge
        if xt:  # what units() would add is cleared with the rest
            st.last_pass = m.pass_no
            st.prev = True
            st.timing = False
            _clear(data, i, st, flags)
            return FFFF
        passed = units()
        falling = st.prev
        st.prev = False
        if falling:
            _clear(data, i, st, flags)
            st.timing = True
            passed = 0
        if not st.timing:  # never switched on since the start: passive, YT = 0
            return 0
        value, now_over = _advance(data, i, st, passed, top)
        _timer_flags(flags, preset, value, st, now_over)
        return FFFF if value < preset else 0

    return tof


def _imp(m: Machine, instr: Instruction) -> Core:
    data, i, flags, st, units, top = _timer_parts(m, instr)

    def imp(xt: int, preset: int) -> int:  # a pulse of the preset's length from a rising edge of XT
        passed = units()
        xt = xt != 0
        rising = xt and not st.prev
        st.prev = xt
        if not st.timing:
            if not rising:
                return 0
            _clear(data, i, st, flags)
            st.timing = True
            passed = 0
        value, now_over = _advance(data, i, st, passed, top)
        _timer_flags(flags, preset, value, st, now_over)
        if value >= preset:
            st.timing = False
            return 0
        return FFFF

    return imp


def _rto(m: Machine, instr: Instruction) -> Core:
    data, i, flags, st, units, top = _timer_parts(m, instr)

    def rto(xt: int, rt: int, preset: int) -> tuple[int, int]:  # A2 XT, A1 RT, A0 preset -> A2 YC, A0 YT
        passed = units(xt != 0 and not rt)
        if rt:  # passive: RT = 1 clears
            st.timing = False
            _clear(data, i, st, flags)
            return 0, 0
        if xt:
            if not st.timing:
                passed = 0
            st.timing = True
            value, now_over = _advance(data, i, st, passed, top)
        else:  # waiting: the content and the flags stay
            st.timing = False
            value, now_over = data[i] | data[i + 1] << 8, False
        _timer_flags(flags, preset, value, st, now_over)
        return FFFF if value >= preset else 0, FFFF if st.overflow else 0

    return rto


# -- the blocks, and their closures on the stack ------------------------------------------------------

COUNTER = Shape(2, True, (0, 2))
UP_DOWN = Shape(3, True, (0, 3, 2))
SHIFT = Shape(2, True, (0, 1))
TIMER = Shape(2, False, (0,), preset=True)
RETENTIVE = Shape(3, False, (0, 2), preset=True)
BLOCKS: dict[str, tuple[Callable[[Machine, Instruction], Core], Shape]] = {
    **dict.fromkeys(("CTU", "CTD"), (_ctu_ctd, COUNTER)),
    "CNT": (_cnt, UP_DOWN),
    **dict.fromkeys(("SFL", "SFR"), (_shift, SHIFT)),
    "TON": (_ton, TIMER),
    "TOF": (_tof, TIMER),
    "IMP": (_imp, TIMER),
    "RTO": (_rto, RETENTIVE),
}
"""Each function block: the builder of its core, and its shape."""


def block(m: Machine, index: int, instr: Instruction) -> Code:
    """The closure running the block of ``instr`` on the active stack."""
    build, shape = BLOCKS[instr.mnemonic]
    core = build(m, instr)
    nxt, n, places = index + 1, shape.inputs, shape.places
    if not shape.push:
        if len(places) == 1:

            def replace_a0() -> int:
                s = m.st
                s[0] = core(s[1], s[0])
                return nxt

            closure = replace_a0
        else:

            def replace() -> int:
                s = m.st
                for level, value in zip(places, core(*s[n - 1 :: -1]), strict=True):
                    s[level] = value
                return nxt

            closure = replace
    else:

        def push() -> int:
            s = m.st
            outputs = core(*s[n - 1 :: -1])
            s.insert(0, outputs[0])
            del s[8]
            for level, value in zip(places[1:], outputs[1:], strict=True):
                s[level] = value
            return nxt

        closure = push
    return closure
