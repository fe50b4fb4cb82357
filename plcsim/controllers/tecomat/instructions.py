"""The plain instructions' builders: each makes the closure that runs one instruction and returns the next index.

:data:`BUILDERS` maps a mnemonic to its builder; function blocks (:mod:`.blocks`) and tables (:mod:`.tables`)
have their own, and :mod:`.linker` picks each instruction's. Every closure is specialised when the program is
linked (the operand's area, byte and bit, the width,
the jump target are constants in it), so a cycle runs no decoding at all. Stack effects follow the
manual's table (``spec/tecomat.md`` §4.3): LD/LDC push; logic and comparisons with an operand overwrite
A0; AND/OR/XOR/ADD without an operand pop; FLG pushes; jumps leave the stack alone.

Choices where the manual is silent (each also a setting where it matters, see :mod:`.settings`):
byte LDC and byte LET leave A0H = 0 (G36); STK replaces A0 by the OR-fold with A0H = 0, no push (G32);
NEG is A0 := NOT A0 (G21); S1.4 is ANL, which equals N4 OR ANL (G5); a comparison sets S0.0..S0.2 and
leaves the other S0 bits (G43); ADD sets S0.0..S0.2 and leaves S0.3, so a program that never sets the
carry-in adds with CI = 0 (G35); calls and returns leave the stack alone, a ninth nested call stops the CPU
(G37); ED/EC inside a subroutine end the calling process; BP n runs P(50 + n) on the program's stack
and flags and restores them afterwards, so a debugging handler never changes what the program computes
(a BP without its handler does nothing).
"""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING

from plcsim.controllers.tecomat.assembly import Instruction, Label
from plcsim.controllers.tecomat.machine import END, END_CYCLE, MAX_NESTING, STACKS, TecomatRuntimeError
from plcsim.controllers.tecomat.memory import Operand

if TYPE_CHECKING:
    from plcsim.controllers.tecomat.machine import Machine

FFFF = 0xFFFF
Code = Callable[[], int]


def _push(m: Machine) -> Callable[[int], None]:
    def push(value: int) -> None:
        s = m.st
        s.insert(0, value)
        del s[8]

    return push


def pop(m: Machine) -> int:
    """Drop one level (A0 <- A1 ... A6 <- A7); A7 gets 0 or keeps its value (setting); returns the old A0."""
    s = m.st
    value = s.pop(0)
    s.append(s[-1] if m.config.pop_fill_keeps_a7 else 0)
    return value


def _area(m: Machine, op: Operand) -> bytearray:
    return m.pad.areas[op.area]


# -- read / write -------------------------------------------------------------------------------------


def _load(m: Machine, index: int, instr: Instruction) -> Code:
    nxt, op, negate = index + 1, instr.arg, instr.mnemonic == "LDC"
    if op.is_immediate:
        value = (~op.value & FFFF) if negate else op.value

        def ld_imm() -> int:
            s = m.st
            s.insert(0, value)
            del s[8]
            return nxt

        return ld_imm
    data, i, b = _area(m, op), op.index, op.bit
    if op.width == "bit":
        on, off = (0, FFFF) if negate else (FFFF, 0)

        def ld_bit() -> int:
            s = m.st
            s.insert(0, on if data[i] >> b & 1 else off)
            del s[8]
            return nxt

        return ld_bit
    if op.width == "byte":
        flip = 0xFF if negate else 0

        def ld_byte() -> int:
            s = m.st
            s.insert(0, data[i] ^ flip)
            del s[8]
            return nxt

        return ld_byte
    if op.width == "long":
        return _load_long(m, nxt, data, i, negate)
    flip = FFFF if negate else 0

    def ld_word() -> int:
        s = m.st
        s.insert(0, (data[i] | data[i + 1] << 8) ^ flip)
        del s[8]
        return nxt

    return ld_word


def _load_long(m: Machine, nxt: int, data: bytearray, i: int, negate: bool) -> Code:
    """LD/LDC of a long: two levels, the low word in A0 and the high one in A1 (``long_low_word_in_a0``)."""
    flip, low_first = FFFF if negate else 0, m.config.long_low_word_in_a0

    def ld_long() -> int:
        s = m.st
        low, high = (data[i] | data[i + 1] << 8) ^ flip, (data[i + 2] | data[i + 3] << 8) ^ flip
        s[0:0] = (low, high) if low_first else (high, low)
        del s[8:]
        return nxt

    return ld_long


def _write(m: Machine, index: int, instr: Instruction) -> Code:
    nxt, op = index + 1, instr.arg
    negate, conditional = instr.mnemonic == "WRC", instr.mnemonic == "PUT"
    data, i, b = _area(m, op), op.index, op.bit
    flags = m.pad.areas["S"]
    if op.width == "long":
        return _write_long(m, nxt, data, i, negate, conditional)
    if op.width == "bit":
        mask, clear = 1 << b, ~(1 << b) & 0xFF

        def wr_bit() -> int:
            if conditional and not flags[1] & 1:
                return nxt
            if (m.st[0] != 0) != negate:
                data[i] |= mask
            else:
                data[i] &= clear
            return nxt

        return wr_bit
    flip = FFFF if negate else 0
    wide = op.width == "word"

    def wr() -> int:
        if conditional and not flags[1] & 1:
            return nxt
        value = m.st[0] ^ flip
        data[i] = value & 0xFF
        if wide:
            data[i + 1] = value >> 8
        return nxt

    return wr


def _write_long(m: Machine, nxt: int, data: bytearray, i: int, negate: bool, conditional: bool) -> Code:
    """WR/WRC/PUT of a long: A0 and A1 as its two words (as LD loads them); the stack is unchanged."""
    flip = FFFF if negate else 0
    low, high = (0, 1) if m.config.long_low_word_in_a0 else (1, 0)
    flags = m.pad.areas["S"]

    def wr_long() -> int:
        if conditional and not flags[1] & 1:
            return nxt
        s = m.st
        a, b = s[low] ^ flip, s[high] ^ flip
        data[i : i + 4] = bytes((a & 0xFF, a >> 8, b & 0xFF, b >> 8))
        return nxt

    return wr_long


# -- logic --------------------------------------------------------------------------------------------

_OPS: dict[str, Callable[[int, int], int]] = {
    "AND": lambda a, b: a & b,
    "OR": lambda a, b: a | b,
    "XOR": lambda a, b: a ^ b,
}


def _logic(m: Machine, index: int, instr: Instruction) -> Code:
    nxt, op = index + 1, instr.arg
    base = {"ANC": "AND", "ORC": "OR", "XOC": "XOR"}.get(instr.mnemonic, instr.mnemonic)
    negate = base != instr.mnemonic
    if op is None:
        return _logic_pop(m, nxt, base)
    combine = _OPS[base]
    if op.is_immediate:
        value = (~op.value & FFFF) if negate else op.value

        def logic_imm() -> int:
            s = m.st
            s[0] = combine(s[0], value)
            return nxt

        return logic_imm
    data, i, b = _area(m, op), op.index, op.bit
    if op.width == "bit":
        on, off = (0, FFFF) if negate else (FFFF, 0)

        def logic_bit() -> int:  # the bit acts on all 16 bits of A0
            s = m.st
            s[0] = combine(s[0], on if data[i] >> b & 1 else off)
            return nxt

        return logic_bit
    flip = 0xFF if negate else 0

    def logic_byte() -> int:  # A0L with the byte; A0H unchanged
        s = m.st
        a = s[0]
        s[0] = a & 0xFF00 | combine(a & 0xFF, data[i] ^ flip) & 0xFF
        return nxt

    return logic_byte


def _logic_pop(m: Machine, nxt: int, base: str) -> Code:
    combine = _OPS[base]

    def logic_stack() -> int:  # A0 <- A1 op A0, the stack drops by one
        a0 = pop(m)
        s = m.st
        s[0] = combine(s[0], a0)
        return nxt

    return logic_stack


def _neg(m: Machine, index: int, instr: Instruction) -> Code:
    nxt = index + 1

    def neg() -> int:
        s = m.st
        s[0] ^= FFFF
        return nxt

    return neg


# -- memory and edge ----------------------------------------------------------------------------------


def _set_res(m: Machine, index: int, instr: Instruction) -> Code:
    nxt, op, setting = index + 1, instr.arg, instr.mnemonic == "SET"
    data, i = _area(m, op), op.index
    if op.width == "bit":
        mask, clear = 1 << op.bit, ~(1 << op.bit) & 0xFF

        def set_res_bit() -> int:
            if m.st[0]:
                if setting:
                    data[i] |= mask
                else:
                    data[i] &= clear
            return nxt

        return set_res_bit

    def set_res_byte() -> int:  # by the mask in A0L
        if setting:
            data[i] |= m.st[0] & 0xFF
        else:
            data[i] &= ~m.st[0] & 0xFF
        return nxt

    return set_res_byte


def _let(m: Machine, index: int, instr: Instruction) -> Code:
    nxt, op = index + 1, instr.arg
    data, i = _area(m, op), op.index
    if op.width == "bit":
        mask, clear = 1 << op.bit, ~(1 << op.bit) & 0xFF

        def let_bit() -> int:
            s = m.st
            old = data[i] & mask
            if s[0]:
                data[i] |= mask
                s[0] = 0 if old else FFFF
            else:
                data[i] &= clear
                s[0] = 0
            return nxt

        return let_bit

    def let_byte() -> int:
        s = m.st
        new, old = s[0] & 0xFF, data[i]
        data[i] = new
        s[0] = new & ~old & 0xFF
        return nxt

    return let_byte


# -- comparison and arithmetic ------------------------------------------------------------------------


def _value(m: Machine, op: Operand) -> Callable[[], int]:
    if op.is_immediate:
        value = op.value
        return lambda: value
    data, i = _area(m, op), op.index
    if op.width == "byte":
        return lambda: data[i]
    return lambda: data[i] | data[i + 1] << 8


_RELATIONS: dict[str, Callable[[int, int], bool]] = {
    "EQ": lambda a, b: a == b,
    "LT": lambda a, b: a < b,
    "GT": lambda a, b: a > b,
}


def _compare(m: Machine, index: int, instr: Instruction) -> Code:
    nxt, op, relation = index + 1, instr.arg, _RELATIONS[instr.mnemonic]
    flags = m.pad.areas["S"]
    with_ci = m.config.ci_in_compare
    operand = _value(m, op) if op is not None else None

    def compare() -> int:
        s = m.st
        if operand is None:
            a, b = s[1], s[0]  # A1 is the left side
        else:
            a, b = s[0], operand()
        if with_ci:
            b += flags[0] >> 3 & 1
        flags[0] = flags[0] & 0xF8 | (a == b) | (a < b) << 1 | (a <= b) << 2
        s[0] = FFFF if relation(a, b) else 0
        return nxt

    return compare


def _add(m: Machine, index: int, instr: Instruction) -> Code:
    nxt, op = index + 1, instr.arg
    flags = m.pad.areas["S"]
    operand = _value(m, op) if op is not None else None

    def add() -> int:
        b = pop(m) if operand is None else operand()
        s = m.st
        total = s[0] + b + (flags[0] >> 3 & 1)
        result, carry = total & FFFF, total > FFFF
        s[0] = result
        flags[0] = flags[0] & 0xF8 | (result == 0) | carry << 1 | (result == 0 or carry) << 2
        return nxt

    return add


# -- stack --------------------------------------------------------------------------------------------


def _stk(m: Machine, index: int, instr: Instruction) -> Code:
    nxt = index + 1

    def stk() -> int:
        s = m.st
        s[0] = sum(1 << k for k in range(8) if s[k])
        return nxt

    return stk


def _swp(m: Machine, index: int, instr: Instruction) -> Code:
    nxt = index + 1

    def swp() -> int:
        s = m.st
        s[0] = s[0] >> 8 | (s[0] & 0xFF) << 8
        return nxt

    return swp


def _pop(m: Machine, index: int, instr: Instruction) -> Code:
    nxt, count = index + 1, instr.arg

    def pop_n() -> int:
        for _ in range(count):
            pop(m)
        return nxt

    return pop_n


def _flg(m: Machine, index: int, instr: Instruction) -> Code:
    nxt = index + 1
    flags = m.pad.areas["S"]
    push = _push(m)

    def flg() -> int:
        a = m.st[0]
        lo, hi = a & 0xFF, a >> 8
        count = a.bit_count()
        flags[1] = count & 0x1F | (lo == 0xFF) << 4 | (hi == 0xFF) << 5 | (lo != 0) << 6 | (hi != 0) << 7
        push(FFFF if a == FFFF else 0)
        return nxt

    return flg


def _chg(m: Machine, index: int, instr: Instruction) -> Code:
    nxt = index + 1
    target, with_flags = STACKS.index(instr.arg[0]), len(instr.arg) == 2

    def chg() -> int:
        m.select(target, with_flags)
        return nxt

    return chg


def _nxt_prv(m: Machine, index: int, instr: Instruction) -> Code:
    nxt, step = index + 1, 1 if instr.mnemonic == "NXT" else -1

    def move() -> int:  # the row of stacks wraps: H -> A, A -> H (not stated; our choice)
        m.select((m.active + step) % len(STACKS))
        return nxt

    return move


# -- organisational -----------------------------------------------------------------------------------


def _nop(m: Machine, index: int, instr: Instruction) -> Code:
    nxt = index + 1
    return lambda: nxt


def _end(m: Machine, index: int, instr: Instruction) -> Code:
    asm = m.asm

    def end() -> int:
        if m.calls:
            raise TecomatRuntimeError(
                f"the subroutine called last ran into 'E {instr.arg}' at {asm.where(index)}: end it with RET"
            )
        return END

    return end


def _end_if(m: Machine, index: int, instr: Instruction) -> Code:
    nxt, direct = index + 1, instr.mnemonic == "ED"

    def end_if() -> int:
        if (m.st[0] != 0) == direct:
            m.calls.clear()
            return END
        return nxt

    return end_if


def _eoc(m: Machine, index: int, instr: Instruction) -> Code:
    return lambda: END_CYCLE


def _bp(m: Machine, index: int, instr: Instruction) -> Code:
    nxt, handler = index + 1, 50 + instr.arg
    if handler not in m.asm.processes:
        return lambda: nxt

    def breakpoint_() -> int:  # the handler sees the stack and flags; the program goes on with them as they were
        calls, m.calls = m.calls, []
        active, levels, flags = m.active, list(m.st), bytes(m.pad.areas["S"][0:2])
        result = m.run_process(handler)
        m.calls = calls
        m.select(active)
        m.st[:] = levels
        m.pad.areas["S"][0:2] = flags
        return END_CYCLE if result == END_CYCLE else nxt

    return breakpoint_


def _target(m: Machine, label: Label) -> int:
    return m.asm.labels[label.name]


def _jump(m: Machine, index: int, instr: Instruction) -> Code:
    nxt, target = index + 1, _target(m, instr.arg)
    backward = target <= index
    condition = {"JMP": None, "JMD": True, "JMC": False}[instr.mnemonic]

    def jump() -> int:
        if condition is not None and (m.st[0] != 0) != condition:
            return nxt
        if backward:
            m.tick()
        return target

    return jump


def _call(m: Machine, index: int, instr: Instruction) -> Code:
    nxt, target = index + 1, _target(m, instr.arg)
    condition = {"CAL": None, "CAD": True, "CAC": False}[instr.mnemonic]

    def call() -> int:
        if condition is not None and (m.st[0] != 0) != condition:
            return nxt
        return _enter(m, nxt, target)

    return call


def _enter(m: Machine, back: int, target: int) -> int:
    if len(m.calls) >= MAX_NESTING:
        raise TecomatRuntimeError(f"a ninth nested subroutine call: the manual allows nesting {MAX_NESTING} deep")
    m.calls.append(back)
    return target


def _indirect(m: Machine, index: int, instr: Instruction) -> Code:
    nxt, calling, process = index + 1, instr.mnemonic == "CAI", instr.process
    asm = m.asm

    def indirect() -> int:
        number = m.st[0] & 0xFF
        target = m.numbered.get(number)
        if target is None:
            known = ", ".join(f"L {n}" for n in sorted(m.numbered)) or "none"
            raise TecomatRuntimeError(
                f"{instr.mnemonic}: A0L = {number}, but there is no label L {number} (labels: {known})"
            )
        if calling:
            if asm.code[target].process != 60:
                raise TecomatRuntimeError(f"CAI: the label L {number} is not in P60, where subroutines live")
            return _enter(m, nxt, target)
        if asm.code[target].process != process:
            raise TecomatRuntimeError(f"JMI: the label L {number} is in another process; a jump stays in its process")
        if target <= index:
            m.tick()
        return target

    return indirect


def _ret(m: Machine, index: int, instr: Instruction) -> Code:
    nxt = index + 1
    condition = {"RET": None, "RED": True, "REC": False}[instr.mnemonic]

    def ret() -> int:
        if condition is not None and (m.st[0] != 0) != condition:
            return nxt
        if not m.calls:
            raise TecomatRuntimeError(f"{instr.mnemonic} outside a subroutine (no CAL/CAD/CAC/CAI called it)")
        return m.calls.pop()

    return ret


BUILDERS: dict[str, Callable[[Machine, int, Instruction], Code]] = {
    **dict.fromkeys(("LD", "LDC"), _load),
    **dict.fromkeys(("WR", "WRC", "PUT"), _write),
    **dict.fromkeys(("AND", "ANC", "OR", "ORC", "XOR", "XOC"), _logic),
    "NEG": _neg,
    **dict.fromkeys(("SET", "RES"), _set_res),
    "LET": _let,
    **dict.fromkeys(("EQ", "LT", "GT"), _compare),
    "ADD": _add,
    "STK": _stk,
    "SWP": _swp,
    "POP": _pop,
    "FLG": _flg,
    "CHG": _chg,
    **dict.fromkeys(("NXT", "PRV"), _nxt_prv),
    **dict.fromkeys(("L", "P"), _nop),
    "E": _end,
    **dict.fromkeys(("ED", "EC"), _end_if),
    "EOC": _eoc,
    "BP": _bp,
    **dict.fromkeys(("JMP", "JMD", "JMC"), _jump),
    **dict.fromkeys(("CAL", "CAD", "CAC"), _call),
    **dict.fromkeys(("JMI", "CAI"), _indirect),
    **dict.fromkeys(("RET", "RED", "REC"), _ret),
}
