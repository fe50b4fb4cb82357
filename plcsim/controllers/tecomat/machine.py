"""The NS950 machine: scratchpad, the eight 8-level stacks, the call stack, and the linked code it runs.

The assembler's instructions are linked once into closures (:func:`plcsim.controllers.tecomat.linker.link`,
called by whoever downloads the program: the CPU): each runs one instruction and returns the index of the
next one, so a process runs as ``while pc >= 0: pc = code[pc]()``. The machine is the bottom of the
controller: the instruction modules build on its state, and it imports none of them. Booleans are 16-bit
masks (a bit LD fills all of A0; a true comparison gives FFFFH); a binary input is the OR of a level's 16 bits.

>>> from plcsim.controllers.tecomat.assembler import assemble
>>> from plcsim.controllers.tecomat.linker import link
>>> m = Machine(assemble("LD X0.0\\nLD R10\\nLD SW 10\\n"))
>>> m.code = link(m)
>>> m.pad.areas["X"][0], m.pad.areas["R"][10], m.pad.areas["S"][10:12] = 1, 0x40, bytes([1, 7])
>>> m.run_process(0)
-1
>>> [hex(v) for v in m.st[:3]]
['0x701', '0x40', '0xffff']
"""

from __future__ import annotations

from collections.abc import Callable

from plcsim.controllers.tecomat.assembly import Assembly
from plcsim.controllers.tecomat.memory import Scratchpad
from plcsim.controllers.tecomat.settings import TecomatConfig
from plcsim.core.errors import PlcError

END = -1
"""A process ended (``E n``, ``ED``, ``EC``)."""
END_CYCLE = -2
"""``EOC``: the cycle ends early."""
MAX_NESTING = 8
STACKS = "ABCDEFGH"
ZEROS = (0,) * 8


class TecomatRuntimeError(PlcError):
    """An error while the program runs (the CPU goes to STOP); ``index`` is the instruction's."""

    def __init__(self, message: str, index: int | None = None):
        super().__init__(message)
        self.index = index


class Machine:
    """The state one Tecomat program runs on, and its linked code."""

    def __init__(self, asm: Assembly, config: TecomatConfig | None = None):
        self.asm = asm
        self.config = config or TecomatConfig()
        cfg = self.config
        self.pad = Scratchpad.sized(x=cfg.x_size, y=cfg.y_size, s=cfg.s_size, r=cfg.r_size, d=asm.data)
        self.stacks = [[0] * 8 for _ in STACKS]
        self.active = 0
        self.st = self.stacks[0]
        """The active stack: ``st[0]`` is A0 (the accumulator), ``st[7]`` is A7."""
        self.saved_flags = [(0, 0)] * len(STACKS)
        self.calls: list[int] = []
        self.t0 = 0
        """The turnaround time of the running cycle (the time every instruction of the pass sees)."""
        self.prev_t0 = 0
        self.pass_no = 0
        self.jumps = 0
        self.tables = {key: list(t.items) for key, t in asm.tables.items()}
        self.blocks: list = []
        """The hidden state of every function block (edge memories, timer phases), reset by a cold restart."""
        self.numbered = {int(name[1:]): i for name, i in asm.labels.items() if name[:1] == "L" and name[1:].isdigit()}
        self.code: list[Callable[[], int]] = []
        """One closure per instruction of ``asm``, set by :func:`plcsim.controllers.tecomat.linker.link`."""

    # -- the stack -----------------------------------------------------------------------------------

    def select(self, k: int, with_flags: bool = False) -> None:
        """Activate stack ``k`` (0 = A); with ``with_flags`` save S0, S1 for the old one, restore the new one's."""
        s = self.pad.areas["S"]
        if with_flags:
            self.saved_flags[self.active] = (s[0], s[1])
            s[0], s[1] = self.saved_flags[k]
        self.active = k % len(STACKS)
        self.st = self.stacks[self.active]

    def turnaround(self, t0: int) -> None:
        """The stack part of the cycle turnaround: stack A cleared (all eight with ``clear_all_stacks``), A active."""
        self.prev_t0, self.t0 = self.t0, t0
        self.pass_no += 1
        self.jumps = 0
        self.calls.clear()
        a = self.stacks[0]
        if self.config.clear_all_stacks:
            for stack in self.stacks:
                stack[:] = ZEROS
        else:
            a[:] = ZEROS
        self.active = 0
        self.st = a

    # -- running -------------------------------------------------------------------------------------

    def run_process(self, number: int) -> int:
        """Run process ``number`` to its end: :data:`END`, or :data:`END_CYCLE` after EOC."""
        code = self.code
        pc = self.asm.processes[number]
        try:
            while pc >= 0:
                pc = code[pc]()
        except TecomatRuntimeError as exc:
            if exc.index is None:
                exc.index = pc
            raise
        return pc

    def tick(self) -> None:
        """A backward jump: the cycle watchdog counts them (a jump loop never hangs the simulation)."""
        self.jumps += 1
        if self.jumps > self.config.watchdog_jumps:
            raise TecomatRuntimeError(
                f"the cycle did not end: more than {self.config.watchdog_jumps} backward jumps in one cycle "
                f"(a jump loop?); the cycle-time watchdog stopped the CPU"
            )

    # -- restarts ------------------------------------------------------------------------------------

    def cold(self) -> None:
        """Cold restart: R cleared, the stacks cleared, every block's hidden state and every table initialised."""
        self._clear(keep=(0, 0))

    def warm(self) -> None:
        """Warm restart: as cold, but the retentive part of R (and the blocks working in it) keeps its state."""
        self._clear(keep=self.config.retentive_r)

    def _clear(self, keep: tuple[int, int]) -> None:
        r = self.pad.areas["R"]
        lo, hi = keep
        kept = bytes(r[lo:hi])
        r[:] = bytes(len(r))
        r[lo:hi] = kept
        for area in "XYU":
            self.pad.areas[area][:] = bytes(len(self.pad.areas[area]))
        s = self.pad.areas["S"]
        s[:] = bytes(len(s))
        for stack in self.stacks:
            stack[:] = [0] * 8
        self.saved_flags = [(0, 0)] * len(STACKS)
        self.select(0)
        for block in self.blocks:
            if not lo <= block.index < hi:
                block.reset()
        for key, table in self.asm.tables.items():
            self.tables[key][:] = table.items
        self.pass_no = 0
        self.t0 = self.prev_t0 = 0
