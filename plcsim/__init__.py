"""plcsim: a teaching simulator of an S7-1200 PLC, its training rigs and graded exercises.

The names here are the ones a program author, a notebook reader or an instructor needs; the
scenario verbs live in :mod:`plcsim.scenario` and the checker language in :mod:`plcsim.check`.
"""

from plcsim.cpu import CPU, RUN, STOP, CPUConfig
from plcsim.errors import PlcError
from plcsim.exercise import Exercise
from plcsim.grading import grade
from plcsim.program import CyclicInterrupt, Program
from plcsim.scenario import Scenario
from plcsim.sim import RealtimeSimulation, Simulation
from plcsim.tags import DB, Tag, TagTable
from plcsim.trace import Trace
from plcsim.types import Bool, DInt, Int, Real, Time
from plcsim.wiring import NC, NO, Wire

__version__ = "0.1.0"

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
