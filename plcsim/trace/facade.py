"""The run's record as a run hands it out: the table of :mod:`plcsim.trace.table` with its exporters as
methods, ``trace.plot()`` (:mod:`plcsim.trace.plot`) and ``trace.to_rrd(path)`` (:mod:`plcsim.trace.rerun`).

The imports go one way: the exporters import the table, this module imports both, and the table knows
neither (a test scans the imports). An exporter is imported only when its method is called, so
recording a run loads neither matplotlib nor rerun.

>>> tr = Trace(["LED"], kinds={"LED": "output"}, types={"LED": "bool"})
>>> tr.add_row(0, 1_000_000, 1, (True,))
>>> isinstance(tr, TraceTable), tr.of_task("OB1").plot is not None, tr.value_at("LED", 1_000_000)
(True, True, True)
"""

from __future__ import annotations

from collections.abc import Sequence
from pathlib import Path
from typing import Any

from plcsim.trace.table import BLOCK, HEAD, GeometryFrame, TraceEvent, TraceTable


class Trace(TraceTable):
    """Columns of a run plus its events and geometry, and their exports (see :class:`TraceTable`).

    Attributes:
        names: the signal names, in column order.
        kinds: name -> ``input``, ``output``, ``memory``, ``db``, ``timer``, ``counter``, ``analog``.
        types: name -> ``bool``, ``int`` or ``real``.
    """

    def to_rrd(self, path: str | Path, **options: Any) -> Path:
        """Export to a rerun recording (see :func:`plcsim.trace.rerun.export_rrd`)."""
        from plcsim.trace.rerun import export_rrd

        return export_rrd(self, path, **options)

    def plot(self, signals: Sequence[str] | None = None, **options: Any) -> Any:
        """A matplotlib timing diagram (see :func:`plcsim.trace.plot.timing_diagram`)."""
        from plcsim.trace.plot import timing_diagram

        return timing_diagram(self, signals, **options)


__all__ = ["BLOCK", "HEAD", "GeometryFrame", "Trace", "TraceEvent", "TraceTable"]
