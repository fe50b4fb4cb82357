"""Edge detection: the contacts -|P|- and -|N|-, P_TRIG/N_TRIG, the coils -(P)- -(N)-, R_TRIG/F_TRIG.

-|P|- and P_TRIG keep their old value in an **edge memory bit** that the instruction reads and
writes at once (a later read of that bit in the same scan sees the new value, textbook §4.2.4). The
bit must be used by one edge instruction only: a P and an N sharing one bit fail as the textbook
says. In a program::

    if P(t.TL, "SB1"):        # rising edge of TL, memory bit SB1
        t.CISLO += 1

R_TRIG and F_TRIG are function blocks with their own instance (``EDGE = R_TRIG()``), called as
``t.EDGE.R_TRIG(CLK=t.TL)``.
"""

from __future__ import annotations

from collections.abc import Callable
from typing import Any

from plcsim.core.errors import PlcTypeError, UnknownTagError, did_you_mean
from plcsim.tags.types import Bool


class EdgeTrigger:
    """An R_TRIG or F_TRIG instance: input CLK, output Q, static Stat_Bit (none retentive)."""

    __slots__ = ("CLK", "Q", "Stat_Bit", "_path")

    def __init__(self, path: str = ""):
        self._path = path
        self.reset()

    def reset(self) -> None:
        """All members FALSE."""
        self.CLK = self.Q = self.Stat_Bit = False

    @staticmethod
    def trace_source(member: str) -> str:
        """The attribute holding ``member`` (an edge instance's members are plain attributes)."""
        return member

    def R_TRIG(self, CLK: bool) -> bool:
        """Q is TRUE for the one call in which CLK went from FALSE to TRUE."""
        if CLK is not True and CLK is not False:
            CLK = Bool.coerce(CLK, f"{self._path}.CLK")
        self.Q = q = CLK and not self.Stat_Bit
        self.CLK = self.Stat_Bit = CLK
        return q

    def F_TRIG(self, CLK: bool) -> bool:
        """Q is TRUE for the one call in which CLK went from TRUE to FALSE."""
        if CLK is not True and CLK is not False:
            CLK = Bool.coerce(CLK, f"{self._path}.CLK")
        self.Q = q = (not CLK) and self.Stat_Bit
        self.CLK = self.Stat_Bit = CLK
        return q

    def __repr__(self) -> str:
        return f"<EDGE {self._path}: CLK={self.CLK} Q={self.Q} Stat_Bit={self.Stat_Bit}>"


BitRef = tuple[dict[str, Any], str, Any]


def bit_resolver(t: Any, resolve_path: Callable[[str], tuple[Any, str]]) -> Callable[[str], BitRef]:
    """Return a cached lookup from a memory-bit name (``"SB1"``, ``"DATA.SB"``, ``"%M2.0"``) to where it lives."""
    cache: dict[str, BitRef] = {}

    def lookup(name: str) -> BitRef:
        ref = cache.get(name)
        if ref is not None:
            return ref
        if not isinstance(name, str):
            raise PlcTypeError(
                f"the edge memory bit must be given by name, e.g. P(t.TL, 'SB1'), not {name!r}; "
                "the instruction needs to write it"
            )
        try:
            container, key = resolve_path(name)
        except UnknownTagError:
            if "." in name or name.strip().startswith("%"):
                raise
            raise UnknownTagError(
                f"the edge memory bit {name!r} is not declared: declare it in the program ({name} = Bool()) or "
                f"in the tag table (a %M bit){did_you_mean(name, t._type.members)}"
            ) from None
        member = container._type.members.get(key)
        if member is None:
            raise UnknownTagError(f"no edge memory bit {name!r}{did_you_mean(key, container._type.members)}")
        if getattr(member.type, "name", "") != "Bool":
            raise PlcTypeError(f"edge memory {name!r} is {member.type.name}; it must be a Bool")
        ref = (container.__dict__, key, container._aliased.get(key))
        cache[name] = ref
        return ref

    lookup.cache = cache  # type: ignore[attr-defined]
    return lookup


def check_bool(value: Any, what: str) -> bool:
    """``value`` if it is a Bool, else the error an edge instruction ``what`` reports (also for generated code)."""
    if value is True or value is False:
        return value
    raise PlcTypeError(f"{what} needs a Bool operand, not {value!r}")


def make_edge_instructions(lookup: Callable[[str], BitRef]) -> dict[str, Callable[..., bool]]:
    """Build P, N, P_TRIG, N_TRIG, P_COIL and N_COIL bound to one CPU's memory."""

    def write(ref: BitRef, value: bool) -> None:
        d, key, cell = ref
        if cell is None:
            d[key] = value
        else:
            cell.write(value)

    cache = lookup.cache  # type: ignore[attr-defined]

    def P(operand: bool, memory: str) -> bool:
        """-|P|-: TRUE for one execution when ``operand`` went FALSE -> TRUE; updates ``memory`` at once."""
        if operand is not True and operand is not False:
            operand = check_bool(operand, "P")
        d, key, cell = cache.get(memory) or lookup(memory)
        old = d[key]
        if old is not operand:
            if cell is None:
                d[key] = operand
            else:
                cell.write(operand)
        return operand and not old

    def N(operand: bool, memory: str) -> bool:
        """-|N|-: TRUE for one execution when ``operand`` went TRUE -> FALSE; updates ``memory`` at once."""
        if operand is not True and operand is not False:
            operand = check_bool(operand, "N")
        d, key, cell = cache.get(memory) or lookup(memory)
        old = d[key]
        if old is not operand:
            if cell is None:
                d[key] = operand
            else:
                cell.write(operand)
        return old and not operand

    def P_COIL(rlo: bool, operand: str, memory: str) -> bool:
        """-(P)-: write TRUE to ``operand`` for the scan in which ``rlo`` rose, else FALSE; passes rlo on."""
        rlo = check_bool(rlo, "P_COIL")
        mem = lookup(memory)
        write(lookup(operand), rlo and not mem[0][mem[1]])
        write(mem, rlo)
        return rlo

    def N_COIL(rlo: bool, operand: str, memory: str) -> bool:
        """-(N)-: write TRUE to ``operand`` for the scan in which ``rlo`` fell, else FALSE; passes rlo on."""
        rlo = check_bool(rlo, "N_COIL")
        mem = lookup(memory)
        write(lookup(operand), (not rlo) and mem[0][mem[1]])
        write(mem, rlo)
        return rlo

    return {"P": P, "N": N, "P_TRIG": P, "N_TRIG": N, "P_COIL": P_COIL, "N_COIL": N_COIL}


EDGE_OPERANDS = {"P": (1,), "N": (1,), "P_TRIG": (1,), "N_TRIG": (1,), "P_COIL": (1, 2), "N_COIL": (1, 2)}
"""The edge instructions with an edge memory bit (each bound to one CPU's memory) -> the positions of
their arguments that name a bit (``P(t.S1, t.SB1)``: ``t.SB1`` is the memory bit, not its value)."""
EDGE_INSTRUCTIONS = tuple(EDGE_OPERANDS)


def bind_edge(name: str) -> Callable[[Any], Callable[..., bool]]:
    """How a CPU (anything with ``t`` and ``resolve_path``) builds the edge instruction ``name``."""

    def bind(host: Any) -> Callable[..., bool]:
        return make_edge_instructions(bit_resolver(host.t, host.resolve_path))[name]

    return bind


# The bodies of P and N written out, for the generated code of a whole task (plcsim.frontends.python.inline):
# the same stores in the same order, on the operand ``OPERAND``, the instruction's ``NAME`` and the memory
# bit ``BIT`` (a plain BOOL of the root dict ``_t_dict``, or of a data block's, ``_t_dict[BLOCK].__dict__``); the
# result is left in ``_r``. A change to P or N
# changes its copy here; tests/frontends/test_inline_differential.py runs random programs both ways.
EDGE_WRITTEN_OUT = """
_x = OPERAND
if _x is not True and _x is not False:
    _x = _edge_bool(_x, NAME)
_old = _t_dict[BIT]
if _old is not _x:
    _t_dict[BIT] = _x
_r = RESULT
"""
EDGE_RESULTS = {"P": "_x and not _old", "N": "_old and not _x"}
