"""plcsim: a teaching simulator of an S7-1200 PLC, its training rigs and graded exercises."""

from plcsim.cpu import CPU, RUN, STOP, CPUConfig
from plcsim.errors import PlcError
from plcsim.program import CyclicInterrupt, Program
from plcsim.tags import DB, Tag, TagTable
from plcsim.types import Bool, DInt, Int, Real, Time

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
    "Bool",
    "Int",
    "DInt",
    "Real",
    "Time",
    "__version__",
]
