"""IEC timers TON, TOF, TP, TONR and the RT / PT coils, as the course textbook describes an S7-1200.

One instance type, ``IEC_TIMER``, serves every box: ``t.T1.TON(IN=..., PT="5s")`` returns Q.
TIME values are integers of milliseconds; ``PT`` also takes a literal such as ``"1s500ms"``.

Two dialects (:class:`TimerDialect`):

* ``s7_1200`` (default): Q and ET are refreshed whenever the program reads them, not only when the
  box runs (textbook §3.6.1, §4.3.11). This is why "Takt 1s" solution 4 never pulses.
* ``iec``: Q and ET change only when the box runs (matiec, CODESYS).

>>> from plcsim.core.clock import Clock
>>> clock = Clock()
>>> t1 = IecTimer(clock, "T1")
>>> t1.TON(IN=True, PT="5ms")
False
>>> clock.now = 5_000_000
>>> t1.Q, t1.ET
(True, 5)
"""

from __future__ import annotations

from enum import StrEnum
from typing import Any

from plcsim.core.errors import PlcTypeError
from plcsim.core.literals import time_ms
from plcsim.tags.types import Bool


class TimerDialect(StrEnum):
    """When a timer's Q and ET are brought up to date."""

    S7_1200 = "s7_1200"
    IEC = "iec"


def preset_ms(value: Any, where: str) -> int:
    """Return a preset as TIME milliseconds (an int of ms or a literal such as ``"10s"``)."""
    cls = value.__class__
    if cls is int:
        return value
    if cls is str:
        return time_ms(value)
    if isinstance(value, int) and cls is not bool:
        return int(value)
    raise PlcTypeError(f"{where}: PT must be a TIME (an int of ms or a literal such as '10s'), not {value!r}")


_NS_PER_MS = 1_000_000

NEGATIVE_PRESET = (
    "The negative range of the TIME data type shown above cannot be used with the timer instructions. Negative PT "
    "(preset time) values are set to zero when the timer instruction is executed. ET (elapsed time) is always a "
    "positive value."
)
"""The S7-1200 System Manual (11/2011, A5E02486680-05, §7.2 Timers, note to Table 7-20): what every box does with a
negative preset; the textbook does not say."""


class IecTimer:
    """An IEC_TIMER instance (instance DB members PT, ET, IN, Q; not retentive by default).

    The box methods return Q, the power flow leaving the box.
    """

    __slots__ = ("PT", "IN", "_q", "_et", "_start", "_running", "_acc", "_kind", "_clock", "_live", "_inert", "_path")

    def __init__(self, clock: Any, path: str = "", *, live: bool = True):
        self._clock, self._path, self._live, self._inert = clock, path, live, False
        self._kind: str | None = None
        self.reset()

    def reset(self) -> None:
        """Back to the start values: PT = ET = T#0ms, IN = Q = FALSE."""
        self.PT = 0
        self.IN = False
        self._q = False
        self._et = 0
        self._start = 0
        self._running = False
        self._acc = 0

    # -- members read by the program ---------------------------------------------------------

    @property
    def Q(self) -> bool:
        """Output Q; under the s7_1200 dialect reading it brings the timer up to date."""
        if self._live and self._running:
            self._refresh(self._clock.now)
        return self._q

    @property
    def ET(self) -> int:
        """Elapsed time in ms; under the s7_1200 dialect reading it brings the timer up to date."""
        if self._live and self._running:
            self._refresh(self._clock.now)
        return self._et

    def peek(self) -> tuple[bool, int]:
        """Q and ET as stored, without refreshing (what a watch table shows; observing changes nothing)."""
        return self._q, self._et

    @staticmethod
    def trace_source(member: str) -> str:
        """The attribute holding ``member`` as last computed: reading it never refreshes the timer (the
        recorder and the watch table observe without changing anything).

        >>> IecTimer.trace_source("ET"), IecTimer.trace_source("PT")
        ('_et', 'PT')
        """
        return {"Q": "_q", "ET": "_et"}.get(member, member)

    def make_inert(self) -> None:
        """The timer does not start from now on: on an S7-1200 a timer whose Q and ET are read nowhere does
        not run (textbook §3.6.1, Fig. 3.197); its boxes return Q as it is."""
        self._inert = True

    def write_member(self, key: str, value: Any) -> None:
        """A program's or an HMI's write of a writable member (PT), converted to ms."""
        if key != "PT":
            raise PlcTypeError(f"{key} of {self!r} cannot be written by the program")
        self.PT = preset_ms(value, f"{self._path}.PT")

    # -- refresh -----------------------------------------------------------------------------

    def _refresh(self, now: int) -> None:
        elapsed = (now - self._start) // _NS_PER_MS
        kind = self._kind
        if kind == "TONR":
            elapsed += self._acc
        if elapsed >= self.PT:
            self._et = self.PT if self.PT > 0 else 0  # ET is never negative, even with a negative PT written
            self._running = False
            self._q = kind == "TON" or kind == "TONR"
        else:
            self._et = elapsed if elapsed > 0 else 0

    # -- boxes -------------------------------------------------------------------------------

    def TON(self, IN: bool, PT: Any) -> bool:
        """On-delay: Q turns TRUE when IN has been TRUE for PT; IN = FALSE resets Q and ET."""
        if self._inert:
            return self._q
        if IN is not True and IN is not False:
            IN = Bool.coerce(IN, f"{self._path}.IN")
        self._kind = "TON"
        if PT.__class__ is not int:
            PT = preset_ms(PT, self._path or "TON")
        if PT < 0:
            PT = 0  # see NEGATIVE_PRESET
        self.PT = PT
        now = self._clock.now
        if IN:
            if not self.IN:
                self._start, self._running, self._et, self._q = now, True, 0, False
        else:
            self._running, self._et, self._q = False, 0, False
        if self._running:
            self._refresh(now)
        self.IN = IN
        return self._q

    def TOF(self, IN: bool, PT: Any) -> bool:
        """Off-delay: Q is TRUE while IN is TRUE and for PT after IN falls; ET stays at PT afterwards."""
        if self._inert:
            return self._q
        if IN is not True and IN is not False:
            IN = Bool.coerce(IN, f"{self._path}.IN")
        self._kind = "TOF"
        if PT.__class__ is not int:
            PT = preset_ms(PT, self._path or "TOF")
        if PT < 0:
            PT = 0  # see NEGATIVE_PRESET
        self.PT = PT
        now = self._clock.now
        if IN:
            self._running, self._et, self._q = False, 0, True
        elif self.IN:
            self._start, self._running = now, True
        if self._running:
            self._refresh(now)
        self.IN = IN
        return self._q

    def TP(self, IN: bool, PT: Any) -> bool:
        """Pulse: a rising edge of IN while not running gives Q = TRUE for PT; edges meanwhile are ignored.

        After the pulse ET stays at PT while IN stays TRUE and returns to 0 once IN is FALSE.
        """
        if self._inert:
            return self._q
        if IN is not True and IN is not False:
            IN = Bool.coerce(IN, f"{self._path}.IN")
        self._kind = "TP"
        if PT.__class__ is not int:
            PT = preset_ms(PT, self._path or "TP")
        if PT < 0:
            PT = 0  # see NEGATIVE_PRESET
        self.PT = PT
        now = self._clock.now
        if self._running:
            self._refresh(now)
        if IN and not self.IN and not self._running:
            self._start, self._running, self._et, self._q = now, True, 0, True
            self._refresh(now)
        if not self._running:
            self._q = False
            if not IN:
                self._et = 0
        self.IN = IN
        return self._q

    def TONR(self, IN: bool, PT: Any, R: bool = False) -> bool:
        """Retentive on-delay: ET accumulates over IN pulses; R resets and dominates.

        Starting needs a rising edge of IN: if IN and R are TRUE and R falls, the timer does not start.
        """
        if self._inert:
            return self._q
        if IN is not True and IN is not False:
            IN = Bool.coerce(IN, f"{self._path}.IN")
        if R is not True and R is not False:
            R = Bool.coerce(R, f"{self._path}.R")
        self._kind = "TONR"
        if PT.__class__ is not int:
            PT = preset_ms(PT, self._path or "TONR")
        if PT < 0:
            PT = 0  # see NEGATIVE_PRESET
        self.PT = PT
        now = self._clock.now
        if R:
            self._running, self._et, self._q, self._acc = False, 0, False, 0
        else:
            if self._running:
                self._refresh(now)
            if IN and not self.IN and self._et < PT:
                self._start, self._running, self._acc = now, True, self._et
            elif not IN and self._running:
                self._acc, self._running = self._et, False
            if self._running:
                self._refresh(now)
        self.IN = IN
        return self._q

    # -- coils -------------------------------------------------------------------------------

    def reset_timer(self) -> None:
        """RT: ET = 0, Q = FALSE; the next box call with IN = TRUE starts the timer again."""
        self._running, self._et, self._q, self._acc, self.IN = False, 0, False, 0, False

    def load_preset(self, value: Any) -> None:
        """The -(PT)- coil: write a new preset."""
        self.PT = preset_ms(value, self._path or "PT")

    def __repr__(self) -> str:
        kind = self._kind or "IEC_TIMER"
        return f"<{kind} {self._path}: IN={self.IN} PT={self.PT} ET={self._et} Q={self._q}>"


def RT(instance: IecTimer) -> None:
    """Reset a timer (the -(RT)- coil). Coils after it in the same rung still saw the old Q."""
    if not isinstance(instance, IecTimer):
        raise PlcTypeError(f"RT needs a timer instance such as t.TON_1, not {instance!r}")
    instance.reset_timer()


def PT(instance: IecTimer, value: Any) -> None:
    """Load a new preset into a timer (the -(PT)- coil)."""
    if not isinstance(instance, IecTimer):
        raise PlcTypeError(f"PT needs a timer instance such as t.TON_1, not {instance!r}")
    instance.load_preset(value)


# The bodies of TON and TOF written out, for the generated code of a whole task
# (plcsim.frontends.python.inline): the same stores in the same order as the methods above, on the instance
# ``INSTANCE`` (evaluated once, first), ``IN`` and the constant ``PRESET``; the result is left in ``_r``. A
# change to a method changes its copy here; tests/frontends/test_inline_differential.py runs random
# programs both ways.
TON_WRITTEN_OUT = """
_i = INSTANCE
_x = IN
if _i._inert:
    _r = _i._q
else:
    if _x is not True and _x is not False:
        _x = _box_bool(_x, _i._path + ".IN")
    _i._kind = "TON"
    _i.PT = PRESET
    _now = _i._clock.now
    if _x:
        if not _i.IN:
            _i._start, _i._running, _i._et, _i._q = _now, True, 0, False
    else:
        _i._running, _i._et, _i._q = False, 0, False
    if _i._running:
        _el = (_now - _i._start) // 1_000_000
        if _el >= PRESET:
            _i._et, _i._running, _i._q = PRESET, False, True
        else:
            _i._et = _el if _el > 0 else 0
    _i.IN = _x
    _r = _i._q
"""
TOF_WRITTEN_OUT = """
_i = INSTANCE
_x = IN
if _i._inert:
    _r = _i._q
else:
    if _x is not True and _x is not False:
        _x = _box_bool(_x, _i._path + ".IN")
    _i._kind = "TOF"
    _i.PT = PRESET
    _now = _i._clock.now
    if _x:
        _i._running, _i._et, _i._q = False, 0, True
    elif _i.IN:
        _i._start, _i._running = _now, True
    if _i._running:
        _el = (_now - _i._start) // 1_000_000
        if _el >= PRESET:
            _i._et, _i._running, _i._q = PRESET, False, False
        else:
            _i._et = _el if _el > 0 else 0
    _i.IN = _x
    _r = _i._q
"""
TIMER_READ = "(_i._q if not ((_i := INSTANCE)._live and _i._running) else _i.Q)"
"""A timer's Q read: the stored value unless it is running (then the property, which refreshes)."""
TIMER_READS = {"Q": "_q", "ET": "_et"}
