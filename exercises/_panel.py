"""What the panel exercises share: seeded press patterns, and the I/O, rig and CPU of the OB30 cases."""

from __future__ import annotations

from plants import Panel
from plcsim.exercise import IO
from plcsim.scenario import press


def press_pattern(button: str, n: int = 12, period_ms: int = 300) -> list:
    """``n`` presses of random length (2..150 ms), one per ``period_ms`` window, at seeded times."""
    actions = []
    for k in range(n):
        start = k * period_ms + 50
        actions += press(button, t=f"{start}ms..{start + 60}ms", hold="2ms..150ms")
    return actions


OB30_IO = [
    IO("TL", "push-button", "Bool", "%I0.0", "NO", comment="address proposed; the textbook gives none"),
    IO("LED", "lamp", "Bool", "%Q0.0", comment="address proposed"),
]
OB30_CPU = {"periods": {"OB30": "1s"}, "interrupt_duration": "1ms"}
"""4.3.19-4.3.22: OB30 with a 1 s period; its execution takes about 1 ms (the textbook)."""


def ob30_panel() -> Panel:
    """The panel of the OB30 cases: the button TL and the lamp LED."""
    return Panel(buttons=("TL",), switches=(), lamps=("LED",))
