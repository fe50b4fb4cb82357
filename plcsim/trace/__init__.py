"""The run's record: the table, its rows as written, and its exporters (timing diagrams, rerun)."""

from plcsim.trace.facade import (
    BLOCK,
    HEAD,
    GeometryFrame,
    Trace,
    TraceEvent,
    TraceTable,
)

__all__ = [
    "BLOCK",
    "HEAD",
    "GeometryFrame",
    "Trace",
    "TraceEvent",
    "TraceTable",
]
