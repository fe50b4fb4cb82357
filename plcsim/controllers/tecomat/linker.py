"""Linking a downloaded program: each instruction of the assembly into the closure that runs it.

The machine (:mod:`plcsim.controllers.tecomat.machine`) holds the state and runs ``code``; the
instruction modules build one closure each (:mod:`.instructions`, :mod:`.blocks`, :mod:`.tables`), and
:mod:`.fused` compiles straight-line runs of them into one function. This module sits above all of
them and is the only one that knows them all: the CPU calls :func:`link` once per download
(``machine.code = link(machine)``), and the machine imports none of the instruction modules.
"""

from __future__ import annotations

from collections.abc import Callable

from plcsim.controllers.tecomat.blocks import BLOCKS, block
from plcsim.controllers.tecomat.fused import Cycle, fuse
from plcsim.controllers.tecomat.instructions import BUILDERS
from plcsim.controllers.tecomat.machine import Machine
from plcsim.controllers.tecomat.tables import TABLES

Code = Callable[[], int]


def link(m: Machine, fuse_runs: bool | None = None, cycle: Cycle | None = None) -> list[Code]:
    """The program's closures, one per instruction (runs fused into generated functions with ``config.fuse``;
    ``fuse_runs=False``: one closure per instruction whatever the configuration, for a per-line online view;
    ``cycle``: the whole cycle of a program of P0 alone as one function, see :func:`.fused.fuse`)."""
    code = []
    for index, instr in enumerate(m.asm.code):
        builder = BUILDERS.get(instr.mnemonic) or (block if instr.mnemonic in BLOCKS else TABLES[instr.mnemonic])
        code.append(builder(m, index, instr))
    return fuse(m, code, cycle) if (m.config.fuse if fuse_runs is None else fuse_runs) else code
