"""Online view of a Tecomat instruction list: each line with the accumulator A0 and A1 after it, as STL
monitoring showed them in STEP 7 (an IL program has no ladder).

:class:`IlMonitor` wraps each linked instruction of the CPU's machine with a closure that notes the active
stack's top two levels after the instruction ran, and in which pass. It only reads the machine: the
program runs exactly as without it (the trace is the same bit for bit). A line the last pass did not run
(a jumped-over part, another process not due) is shown without values. The machine is linked again
without fused runs (one closure per instruction, the same semantics), so that every line has its values.
"""

from __future__ import annotations

import html
from collections.abc import Callable
from typing import Any

from plcsim.ladder.svg import FONT, MONO, NO_POWER, POWER


class IlMonitor:
    """Per-instruction values of a :class:`~plcsim.controllers.tecomat.cpu.TecomatCPU`'s last pass."""

    def __init__(self, cpu: Any):
        self.cpu = cpu
        self.values: dict[int, tuple[int, int, int]] = {}
        """Instruction index -> (pass number, A0, A1) when it last ran."""
        self._machine: Any = None

    def attach(self) -> None:
        """Wrap the machine's instructions (again after a download, which links a new machine)."""
        machine = self.cpu.machine
        if machine is None or machine is self._machine:
            return
        from plcsim.controllers.tecomat.linker import link

        self._machine = machine
        self.values.clear()
        machine.code = [self._noting(machine, i, step) for i, step in enumerate(link(machine, fuse_runs=False))]

    def _noting(self, machine: Any, index: int, step: Callable[[], int]) -> Callable[[], int]:
        values = self.values

        def run() -> int:
            after = step()
            st = machine.st
            values[index] = (machine.pass_no, st[0], st[1])
            return after

        return run

    def lines(self, source: str) -> list[tuple[int, str, tuple[int, int] | None]]:
        """(line number, text, (A0, A1) after it in the last pass, or None) for every line of ``source``."""
        self.attach()
        machine = self._machine
        if machine is None:
            return []
        by_line: dict[int, tuple[int, int]] = {}
        for index, instruction in enumerate(machine.asm.code):
            noted = self.values.get(index)
            if noted is not None and noted[0] == machine.pass_no:
                by_line[instruction.line] = (noted[1], noted[2])
        text = source.splitlines() or [f"{i.mnemonic} {i.arg}" for i in machine.asm.code]
        return [(n, line, by_line.get(n)) for n, line in enumerate(text, start=1)]


def render_il_svg(rows: list[tuple[int, str, tuple[int, int] | None]], title: str = "") -> str:
    """The listing with A0 and A1 beside each line that ran (green where A0 is non-zero: its RLO is 1)."""
    line_h, top = 17, 36 if title else 14
    col = 70 + int(7.3 * max((len(text) for _, text, _ in rows), default=20)) + 24
    width = col + 120
    height = top + line_h * (len(rows) + 1) + 10
    out = [
        f'<svg xmlns="http://www.w3.org/2000/svg" class="il" width="{width}" height="{height}" '
        f'viewBox="0 0 {width} {height}" style="background:#fff;{FONT}">'
    ]
    if title:
        out.append(f'<text x="12" y="22" font-size="14" font-weight="bold">{html.escape(title)}</text>')
    y = top + 12
    out.append(f'<text x="{col}" y="{y}" font-size="11" fill="#666">A0</text>')
    out.append(f'<text x="{col + 60}" y="{y}" font-size="11" fill="#666">A1</text>')
    for number, text, values in rows:
        y += line_h
        out.append(f'<text x="12" y="{y}" font-size="11" fill="#999" style="{MONO}">{number:4d}</text>')
        out.append(
            f'<text x="52" y="{y}" font-size="12" style="{MONO}" xml:space="preserve">{html.escape(text)}</text>'
        )
        if values is not None:
            a0, a1 = values
            colour = POWER if a0 else NO_POWER
            out.append(
                f'<g class="il-line" data-line="{number}" data-a0="{a0}">'
                f'<text x="{col}" y="{y}" font-size="12" fill="{colour}" style="{MONO}">{a0:04X}</text>'
                f'<text x="{col + 60}" y="{y}" font-size="12" fill="#444" style="{MONO}">{a1:04X}</text></g>'
            )
    out.append("</svg>")
    return "".join(out)
