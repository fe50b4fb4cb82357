"""plcsim: a teaching simulator of an S7-1200 PLC, its training rigs and graded exercises.

The names here are the ones a program author, a notebook reader or an instructor needs; the
scenario verbs live in :mod:`plcsim.scenario` and the checker language in :mod:`plcsim.check`. The
packages, one per job, are drawn in ``docs/architecture.md``; the module paths of plcsim 0.1 still import
for one release (:mod:`plcsim.core.moved`).
"""

import plcsim.core.startup  # noqa: F401 - first: `python -m plcsim` imports nothing from the current folder
from plcsim.controllers.s7.cpu import CPU, RUN, STOP, CPUConfig
from plcsim.core import moved
from plcsim.core.errors import PlcError
from plcsim.core.version import __version__
from plcsim.exercise.model import Exercise
from plcsim.frontends.python.names import CyclicInterrupt
from plcsim.frontends.python.program import Program
from plcsim.grading.grader import grade
from plcsim.scenario.planning import Scenario
from plcsim.sim.simulation import RealtimeSimulation, Simulation
from plcsim.sim.wiring import NC, NO, Wire
from plcsim.tags.table import DB, Tag, TagTable
from plcsim.tags.types import Bool, DInt, Int, Real, Time
from plcsim.trace.facade import Trace

moved.install()

__all__ = [
    "CPU",
    "CPUConfig",
    "RUN",
    "STOP",
    "Program",
    "CyclicInterrupt",
    "Tag",
    "DB",
    "TagTable",
    "PlcError",
    "Simulation",
    "RealtimeSimulation",
    "Scenario",
    "Trace",
    "Wire",
    "NO",
    "NC",
    "Exercise",
    "grade",
    "Bool",
    "Int",
    "DInt",
    "Real",
    "Time",
    "__version__",
]
