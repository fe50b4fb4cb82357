"""Machine models (plants) of the training rigs, built from ``plants.components`` on the ``plcsim.plant`` protocol.

``RIGS`` maps the plant ids of ``spec/exercises.md`` §0.5 to factories: ``RIGS["CONV1"](end="stop")`` builds a rig.
"""

from collections.abc import Callable

from plants.align import Align
from plants.components import StationOccupiedError
from plants.conveyors import Conv1, Conv2x2, Conv3, ConveyorLine
from plants.machine import Machine
from plants.panel import Panel
from plants.punch import Punch
from plants.sort import Sort

RIGS: dict[str, Callable[..., object]] = {
    "PANEL": Panel,
    "CONV1": Conv1,
    "CONV3": Conv3,
    "CONV2x2": Conv2x2,
    "MACHINE": Machine,
    "ALIGN": Align,
    "SORT": Sort,
    "PUNCH": Punch,
}

__all__ = [
    "RIGS",
    "Align",
    "Conv1",
    "Conv2x2",
    "Conv3",
    "ConveyorLine",
    "Machine",
    "Panel",
    "Punch",
    "Sort",
    "StationOccupiedError",
]
