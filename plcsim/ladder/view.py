"""A program's ladder as an object for notebooks, the command line and reports: SVG, PNG, ``_repr_svg_``.

>>> from plcsim.ladder.view import Ladder
>>> svg = Ladder.from_source("def OB1(t):\\n    t.LED = t.S1 and not t.S2\\n").svg()
>>> svg.startswith("<svg") and '"LED"' in svg
True
"""

from __future__ import annotations

from pathlib import Path
from typing import Any

from plcsim.core.errors import ConfigurationError
from plcsim.frontends.python.program import Program
from plcsim.ladder.build import build_ladder
from plcsim.ladder.model import Block, Network
from plcsim.ladder.monitor import PowerFlow
from plcsim.ladder.snapshot import TraceTags
from plcsim.ladder.svg import Flow, Values, render_svg
from plcsim.tags.table import TagTable


class Ladder:
    """The LAD picture of a Python program (every task, networks in order)."""

    def __init__(self, program: Program, table: TagTable | None = None, title: str | None = None):
        self.program = program
        self.blocks: list[Block] = build_ladder(program, table)
        self.title = Path(program.filename).name if title is None else title

    @classmethod
    def from_file(cls, path: str | Path, table: TagTable | None = None) -> Ladder:
        return cls(Program.from_file(path), table)

    @classmethod
    def from_source(cls, source: str, table: TagTable | None = None) -> Ladder:
        return cls(Program.from_source(source), table, title="")

    def networks(self, names: set[str] | None = None) -> list[Network]:
        """The networks of every task in order, each task's name in its title when there are several;
        ``names`` keeps only those networks (the ones a report needs)."""
        out = []
        for block in self.blocks:
            for net in block.networks:
                if names is None or net.name in names:
                    out.append(net)
        return out

    def svg(self, flow: Flow | None = None, values: Values | None = None, names: set[str] | None = None) -> str:
        """The picture as SVG text; ``flow``/``values`` colour it as TIA's online view does."""
        titles = [b.name for b in self.blocks]
        title = " — ".join(p for p in (self.title, ", ".join(titles)) if p)
        return render_svg(self.networks(names), title, flow, values)

    def monitor(self, tags: Any, names: set[str] | None = None) -> str:
        """The picture with power flow for the CPU's tags now (``cpu.t``), as TIA's online view shows it."""
        flow = PowerFlow(self.networks(names), tags, self.program.constants)
        return self.svg(flow, flow.value, names)

    def at_trace(self, trace: Any, t_ns: int, names: set[str] | None = None) -> str:
        """The picture with the power flow of the scan a trace recorded at ``t_ns`` (what was not
        recorded is drawn unmonitored)."""
        flow = PowerFlow(self.networks(names), TraceTags(trace, t_ns), self.program.constants)
        return self.svg(flow, flow.value, names)

    def png(self, flow: Flow | None = None, values: Values | None = None, zoom: float = 1.5) -> bytes:
        """The same picture as PNG (for reports); needs the optional package resvg-py."""
        return svg_to_png(self.svg(flow, values), zoom)

    def _repr_svg_(self) -> str:
        return self.svg()


def svg_to_png(svg: str, zoom: float = 1.5) -> bytes:
    """Render SVG text to PNG bytes with resvg (a wheel on Windows, macOS and Linux, no system library)."""
    try:
        import resvg_py  # optional: only PNG needs it
    except ImportError:
        raise ConfigurationError(
            "drawing a ladder as PNG needs the package resvg-py: pip install 'plcsim[png]' (or write .svg)"
        ) from None
    return bytes(resvg_py.svg_to_bytes(svg_string=svg, zoom=zoom, background="#ffffff"))
