"""IEC counters CTU, CTD, CTUD (instance type ``IEC_COUNTER``), as the textbook describes them.

CU and CD count on rising edges; R resets CV to 0 and dominates LD, which loads PV. QU = CV >= PV,
QD = CV <= 0 (so QD is TRUE at the start). Counting past the type's limits **wraps** (the textbook,
§3.7.1: past 32 767 comes -32 768, and QU drops); IEC's saturation is selectable per CPU.
The instance is retentive by default, as in the textbook's Fig. 3.233.

>>> c = IecCounter()
>>> [c.CTU(CU=cu, PV=2) for cu in (True, False, True, True)]
[False, False, True, True]
>>> c.CV
2
"""

from __future__ import annotations

from typing import Any

from plcsim.core.errors import ConfigurationError, PlcTypeError
from plcsim.tags.types import Bool, ElementaryType, Int


class IecCounter:
    """An IEC_COUNTER instance: members CU, CD, R, LD, QU, QD, PV, CV."""

    __slots__ = ("CU", "CD", "R", "LD", "QU", "QD", "PV", "CV", "_lo", "_hi", "_saturate", "_type", "_path", "_kind")

    def __init__(self, value_type: ElementaryType = Int, *, saturate: bool = False, path: str = ""):
        if not isinstance(value_type, ElementaryType) or value_type.kind != "int":
            raise ConfigurationError(
                f"{path or 'IEC_COUNTER'}: the count type must be an integer type such as "
                f"Int or DInt, not {value_type!r}"
            )
        self._type, self._lo, self._hi = value_type, value_type.lo, value_type.hi
        self._saturate, self._path = saturate, path
        self._kind: str | None = None
        self.reset()

    def reset(self) -> None:
        """Start values: every input FALSE, PV = CV = 0, QU = FALSE, QD = TRUE."""
        self.CU = self.CD = self.R = self.LD = False
        self.QU = False
        self.QD = True
        self.PV = 0
        self.CV = 0

    @property
    def Q(self) -> bool:
        """QU for a CTU, QD for a CTD."""
        return self.QD if self._kind == "CTD" else self.QU

    @staticmethod
    def trace_source(member: str) -> str:
        """The attribute holding ``member`` (a counter's members are plain attributes)."""
        return member

    def write_member(self, key: str, value: Any) -> None:
        """A program's or an HMI's write of a writable member (CV, PV), converted to the count type."""
        if key not in ("CV", "PV"):
            raise PlcTypeError(f"{key} of {self!r} cannot be written by the program")
        setattr(self, key, self._type.coerce(value, f"{self._path}.{key}"))

    def _step(self, cv: int, delta: int) -> int:
        cv += delta
        if self._lo <= cv <= self._hi:
            return cv
        if self._saturate:
            return self._hi if cv > self._hi else self._lo
        span = self._hi - self._lo + 1
        return (cv - self._lo) % span + self._lo

    def _preset(self, PV: Any) -> int:
        if PV.__class__ is not int:
            if not isinstance(PV, int) or isinstance(PV, bool):
                raise PlcTypeError(f"{self._path or 'counter'}: PV must be an integer, not {PV!r}")
            PV = int(PV)
        if not self._lo <= PV <= self._hi:
            raise PlcTypeError(
                f"{self._path or 'counter'}: PV {PV} is outside the count type's range {self._lo}..{self._hi}"
            )
        return PV

    def _bools(self, *operands: tuple[str, Any]) -> list[bool]:
        """The box's BOOL inputs, refused when they are not Bools (a 2 or a function never lands in CU)."""
        return [v if v is True or v is False else Bool.coerce(v, f"{self._path}.{name}") for name, v in operands]

    def CTUD(self, CU: bool = False, CD: bool = False, R: bool = False, LD: bool = False, PV: Any = 0) -> bool:
        """Count up on CU edges and down on CD edges; returns QU."""
        self._kind = self._kind or "CTUD"
        CU, CD, R, LD = self._bools(("CU", CU), ("CD", CD), ("R", R), ("LD", LD))
        pv = self._preset(PV)
        cv = self.CV
        if R:
            cv = 0
        elif LD:
            cv = pv
        else:
            if CU and not self.CU:
                cv = self._step(cv, 1)
            if CD and not self.CD:
                cv = self._step(cv, -1)
        self.CV, self.PV, self.CU, self.CD, self.R, self.LD = cv, pv, CU, CD, R, LD
        self.QU = cv >= pv
        self.QD = cv <= 0
        return self.QU

    def CTU(self, CU: bool, R: bool = False, PV: Any = 0) -> bool:
        """Count up on CU edges, reset with R; returns Q = CV >= PV."""
        self._kind = "CTU"
        if (CU is not True and CU is not False) or (R is not True and R is not False):
            CU, R = self._bools(("CU", CU), ("R", R))
        pv = self._preset(PV)
        if R:
            cv = 0
        elif CU and not self.CU:
            cv = self._step(self.CV, 1)
        else:
            cv = self.CV
        self.CV, self.PV, self.CU, self.R = cv, pv, CU, R
        self.QU = cv >= pv
        self.QD = cv <= 0
        return self.QU

    def CTD(self, CD: bool, LD: bool = False, PV: Any = 0) -> bool:
        """Count down on CD edges, load PV with LD; returns Q = CV <= 0."""
        self._kind = "CTD"
        if (CD is not True and CD is not False) or (LD is not True and LD is not False):
            CD, LD = self._bools(("CD", CD), ("LD", LD))
        pv = self._preset(PV)
        if LD:
            cv = pv
        elif CD and not self.CD:
            cv = self._step(self.CV, -1)
        else:
            cv = self.CV
        self.CV, self.PV, self.CD, self.LD = cv, pv, CD, LD
        self.QU = cv >= pv
        self.QD = cv <= 0
        return self.QD

    def __repr__(self) -> str:
        return f"<{self._kind or 'IEC_COUNTER'} {self._path}: CV={self.CV} PV={self.PV} QU={self.QU} QD={self.QD}>"


# The body of CTU written out, for the generated code of a whole task (plcsim.frontends.python.inline): the
# same stores in the same order as the method above, on the instance ``INSTANCE`` (evaluated once, first),
# the call's CU and R (``ARGUMENTS`` sets ``_cu`` and ``_rs`` in the call's order) and the constant
# ``PRESET``; the result is left in ``_r``. A change to CTU changes its copy here;
# tests/frontends/test_inline_differential.py runs random programs both ways.
CTU_WRITTEN_OUT = """
_i = INSTANCE
ARGUMENTS
_i._kind = "CTU"
if (_cu is not True and _cu is not False) or (_rs is not True and _rs is not False):
    _cu, _rs = _i._bools(("CU", _cu), ("R", _rs))
_pv = PRESET
if not _i._lo <= _pv <= _i._hi:
    _pv = _i._preset(_pv)
if _rs:
    _cv = 0
elif _cu and not _i.CU:
    _cv = _i.CV + 1
    if _cv > _i._hi:
        _cv = _i._step(_i.CV, 1)
else:
    _cv = _i.CV
_i.CV, _i.PV, _i.CU, _i.R = _cv, _pv, _cu, _rs
_i.QU = _r = _cv >= _pv
_i.QD = _cv <= 0
"""
