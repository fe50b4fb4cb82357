"""PLC836 step mechanisms (the "logical sequential units" of seed 003, chapter 4) as an instance type.

A mechanism is a sequence of states: an action writes bits, a state waits for a condition. It runs
while its activation bit ``ACTIVE`` is set and clears the bit itself when it falls through its end.
Declared as ``CWCCW = MECHANISM()`` and written as ``if`` blocks, one per step::

    def cwccw(t):
        if t.CWCCW.begin():                          # MECH_BEGIN: False while the bit is 0
            if t.CWCCW.step(1):                      # the window of step 1: runs again every scan it waits
                t.SMP = False
                t.CWCCW.wait_while(t.KSMP, timeout="1s", error="CW_ERR", code=4)   # TEX1
            if t.CWCCW.step(2):
                t.CWCCW.delay("200ms")               # TIM
            if t.CWCCW.error("CW_ERR"):              # the label a timeout jumps to
                t.BZH11 = t.CWCCW.ERR
            t.CWCCW.end()                            # MECH_END: falls through -> ACTIVE = FALSE

The chapter's two subtleties hold by construction: the code of the step the mechanism waits in runs
again every scan (the window between the last passed state and the blocking one, §6.2 a), and a state
whose condition already holds passes at once, so the next step's ``if`` runs in the same scan and a
whole sequence can finish in one scan (§6.2 b). The CPU option ``mechanism_mode="iec"`` makes it
advance at most one step per scan instead (IEC 61131-3 SFC; the end is a step of its own there).

The ``.mech`` front end (:mod:`plcsim.frontends.mech`) drives the same instance through
:meth:`Mechanism.state`, so the same program in both forms records the same trace.

>>> from plcsim.core.clock import Clock
>>> clock = Clock()
>>> m = Mechanism(clock, "M")
>>> m.ACTIVE = True
>>> m.begin(), m.step(1), m.wait_until(True), m.step(2), m.wait_until(True), m.end()
(True, True, True, True, True, True)
>>> m.ACTIVE, m.STEP
(False, 0)
"""

from __future__ import annotations

import functools
from typing import Any

from plcsim.core.errors import PlcTypeError, ProgramError
from plcsim.core.literals import time_ms
from plcsim.tags.types import Bool

PLC836 = "plc836"
IEC = "iec"
MODES = (PLC836, IEC)

PASS, HOLD, TIMEOUT = 0, 1, 2
"""What a state did in this pass: passed (the next step follows), held (the pass ends), timed out."""

EX, EX0, EX1, BEX, TIM = "EX", "EX0", "EX1", "BEX", "TIM"
"""State kinds, as the chapter names them (TEX0/TEX1 are EX0/EX1 with a timeout)."""

_NS_PER_MS = 1_000_000


@functools.lru_cache(maxsize=256)
def _literal_ms(text: str) -> int:
    return time_ms(text)


def duration_ms(value: Any, where: str) -> int:
    """A timeout or a delay as milliseconds: an int of ms or a TIME literal such as ``"1s"``."""
    if value.__class__ is int:
        return value
    if value.__class__ is str:
        return _literal_ms(value)
    raise PlcTypeError(f"{where}: a time is an int of ms or a literal such as '1s', not {value!r}")


class Mechanism:
    """A MECHANISM instance: the activation bit, the step it is in, how long it has been there, its error.

    Members (read by the program, the trace and the checks): ``ACTIVE`` (the activation bit; writing
    TRUE starts the mechanism, as ``FL 1,NAME`` does), ``STEP`` (0 idle, else the step it waits in),
    ``ET`` (ms in that step), ``ERR`` (the code of the last timeout of this run, 0 if none; cleared when
    a run starts), ``LINE`` (``NAME_LINE``: the listing line of the state it waits at in a ``.mech``
    file, the step number in Python).
    """

    __slots__ = (
        "ACTIVE",
        "STEP",
        "ET",
        "ERR",
        "LINE",
        "cont",
        "branch",
        "history",
        "_clock",
        "_path",
        "_iec",
        "_entered",
        "_entered_pass",
        "_pass",
        "_in_pass",
        "_held",
        "_moved",
        "_open",
        "_evaluated",
    )

    def __init__(self, clock: Any, path: str = "", *, mode: str = PLC836):
        if mode not in MODES:
            raise PlcTypeError(f"mechanism_mode {mode!r}: use 'plc836' or 'iec'")
        self._clock, self._path, self._iec = clock, path, mode == IEC
        self.reset()

    def reset(self) -> None:
        """The idle state at STOP -> RUN (MECH_INIT, and the history forgotten)."""
        self.history: list[tuple[int, int, int]] = []
        self._pass = 0
        self._init()

    def _init(self) -> None:
        self.ACTIVE = False
        self.STEP = 0
        self.ET = 0
        self.LINE = 0
        self.ERR = 0
        self.cont = 0
        """The ``.mech`` front end's continuation address (the chapter's automatic WORD cell)."""
        self.branch: str | None = None
        """The error label the last timeout jumped to, while the run is in that branch."""
        self._entered = 0
        self._entered_pass = 0
        self._in_pass = self._held = self._moved = self._evaluated = False
        self._open = 0

    @property
    def iec(self) -> bool:
        """Whether it advances at most one step per scan (the CPU's ``mechanism_mode="iec"``)."""
        return self._iec

    @staticmethod
    def trace_source(member: str) -> str:
        """The attribute holding ``member`` (reading it changes nothing)."""
        return member

    def write_member(self, key: str, value: Any) -> None:
        """A program's or an HMI's write of ``ACTIVE`` (the only writable member)."""
        if key != "ACTIVE":
            raise PlcTypeError(f"{key} of {self!r} cannot be written by the program")
        self.ACTIVE = value if value is True or value is False else Bool.coerce(value, f"{self._path}.ACTIVE")

    # -- MECH_BEGIN / MECH_END / MECH_INIT --------------------------------------------------

    def begin(self) -> bool:
        """MECH_BEGIN: whether the mechanism runs in this pass (its bit is set); a run starts at step 1."""
        self._pass += 1
        self._held = self._moved = False
        self._open = 0
        if not self.ACTIVE:
            self._in_pass = False
            return False
        self._in_pass = True
        if self.STEP == 0 and self.branch is None:
            self.ERR = 0
            self.history = []
            self._enter(1)
        return True

    def end(self) -> bool:
        """MECH_END: a pass that reaches it with no state holding ends the run (ACTIVE, STEP, ET, LINE
        back to 0); True if the run ended now."""
        if not self._in_pass:
            return False
        self._in_pass = False
        if self._held or (self._iec and self._moved):
            return False
        self._leave()
        self.ACTIVE = False
        self.STEP = self.ET = self.LINE = self.cont = 0
        self.branch = None
        return True

    def init(self) -> bool:
        """MECH_INIT: back to idle (bit cleared, next run from the top); outputs stay as they are. False."""
        self._leave()
        self._init()
        return False

    def start(self) -> bool:
        """FL 1,NAME: set the activation bit (no effect on a run in progress). True."""
        self.ACTIVE = True
        return True

    # -- the Python form: steps and their states ---------------------------------------------

    def step(self, n: int) -> bool:
        """Whether the code of step ``n`` runs in this pass: the mechanism is in step ``n`` and (IEC
        mode) has not advanced already in this pass. Its code ends with one state (a wait, a delay,
        ``ex`` or ``bex``)."""
        if not self._in_pass or self._held or n != self.STEP or self.branch is not None:
            return False
        if self._iec and self._moved:
            return False
        self._open = n
        return True

    def goto(self, n: int) -> bool:
        """JUM: go on in step ``n`` (its code runs in the next scan: a Python program runs top to bottom),
        leaving an error branch. True."""
        if self._in_pass and not self._held:
            self.branch = None
            self._enter(n)
            self._held = True  # the rest of this pass is skipped: step n runs from the next scan
            self._open = 0
        return True

    def error(self, label: str) -> bool:
        """Whether this pass runs the error branch ``label`` (a timeout with ``error=label`` jumped here)."""
        if not self._in_pass or self._held or self.branch != label:
            return False
        return not (self._iec and self._moved)

    def wait_until(self, condition: bool, timeout: Any = None, error: str = "", code: int = 0) -> bool:
        """EX0 (TEX0 with a timeout): wait until ``condition`` is TRUE; True if it passed now. After
        ``timeout`` the run jumps to ``error(error)`` with ``ERR = code``."""
        return self._python_state(EX0, condition, timeout, error, code) == PASS

    def wait_while(self, condition: bool, timeout: Any = None, error: str = "", code: int = 0) -> bool:
        """EX1 (TEX1 with a timeout): wait while ``condition`` is TRUE; True if it passed now."""
        return self._python_state(EX1, condition, timeout, error, code) == PASS

    def delay(self, time: Any) -> bool:
        """TIM: stay in this step for ``time`` (at least one scan); True when it passed."""
        return self._python_state(TIM, False, time, "", 0) == PASS

    def ex(self) -> bool:
        """EX: stay in this step for exactly one scan; True when it passed."""
        return self._python_state(EX, False, None, "", 0) == PASS

    def bex(self) -> bool:
        """BEX: end this step's actions without losing a scan (the next step's code runs again each
        scan it waits, these actions do not). True."""
        return self._python_state(BEX, False, None, "", 0) == PASS

    def _python_state(self, kind: str, condition: Any, timeout: Any, label: str, code: int) -> int:
        n = self._open
        if not n:
            raise ProgramError(
                f"{self._path}: a wait, delay, ex or bex runs only inside its step: "
                f"write it under `if t.{self._path}.step(n):`"
            )
        self._open = 0
        if condition is not True and condition is not False:
            condition = Bool.coerce(condition, f"{self._path} condition")
        limit = None if timeout is None else duration_ms(timeout, f"{self._path} step {n}")
        if limit is not None and kind != TIM and not label:
            raise ProgramError(f"{self._path} step {n}: a timeout needs error='LABEL' to jump to")
        return self.state(kind, n, n, condition, limit, label, code)

    # -- the shared core (the .mech front end calls it directly) -------------------------------

    def state(
        self,
        kind: str,
        n: int,
        line: int,
        condition: bool,
        limit_ms: int | None,
        label: str,
        code: int,
        counter: list[int] | None = None,
    ) -> int:
        """Evaluate state ``n`` (written at ``line``) of kind EX/EX0/EX1/BEX/TIM in this pass.

        EX0 blocks while ``condition`` is FALSE, EX1 while it is TRUE (the digit names the blocking
        value); ``limit_ms`` is TEX's time (TIM's delay) and ``label``/``code`` its error exit. The time
        counts from the scan the state was entered in, or on ``counter`` (a named ``citac`` of a
        ``.mech`` file, ``[start ns]``): every state that names it restarts it when entered, whichever
        mechanism it is in. Returns PASS (the mechanism is in step ``n + 1`` now), HOLD (the pass ends)
        or TIMEOUT (``branch = label``, ``ERR = code``)."""
        now = self._clock.now
        if n != self.STEP:  # arrived by a jump (a .mech loop, or states inside an error branch)
            self._enter(n)
        if not self._evaluated:  # reached for the first time: its time starts now (a scan after the
            self._evaluated = True  # advance in the one-step-per-scan mode, in the same scan otherwise)
            self._entered = now
            if counter is not None:
                counter[0] = now
        self.LINE = line
        elapsed = (now - (self._entered if counter is None else counter[0])) // _NS_PER_MS
        self.ET = elapsed
        if kind == EX0:
            blocked = not condition
        elif kind == EX1:
            blocked = condition
        elif kind == TIM:
            blocked = elapsed < (limit_ms or 0) or self._pass == self._entered_pass
            limit_ms = None
        elif kind == EX:
            blocked = self._pass == self._entered_pass
        else:  # BEX
            blocked = False
        if not blocked:
            self._moved = True
            self._enter(n + 1)
            return PASS
        if limit_ms is not None and elapsed >= limit_ms:
            self._moved = True
            self.ERR = code
            self.branch = label
            return TIMEOUT
        self._held = True
        return HOLD

    def _enter(self, n: int) -> None:
        now = self._clock.now
        self._leave()
        self.STEP = n
        self.ET = 0
        self._entered = now
        self._entered_pass = self._pass
        self._evaluated = False

    def _leave(self) -> None:
        if self.STEP:
            self.history.append((self.STEP, self._entered, self._clock.now))
            if len(self.history) > 64:
                del self.history[0]

    def __repr__(self) -> str:
        return f"<MECHANISM {self._path}: ACTIVE={self.ACTIVE} STEP={self.STEP} ET={self.ET} ERR={self.ERR}>"
