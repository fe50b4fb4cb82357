"""Machine models (plants) of the training rigs, built from ``plants.components`` on the ``plcsim.plant`` protocol.

The rigs are registered with plcsim by their plant ids of ``spec/exercises.md`` §0.5 (``pyproject.toml``,
``[project.entry-points."plcsim.rigs"]``); ``RIGS`` is that registry: ``RIGS["CONV1"](end="stop")`` builds a rig.
"""

from collections.abc import Callable, Iterator, Mapping

from plants.align import Align
from plants.components import StationOccupiedError
from plants.conveyors import Conv1, Conv2x2, Conv3, ConveyorLine
from plants.hbw import HBW
from plants.machine import Machine
from plants.panel import Panel
from plants.punch import Punch
from plants.skip import Skip
from plants.slide import Slide
from plants.sort import Sort
from plants.spindle import Spindle
from plcsim.core import registry


class _Registered(Mapping[str, Callable[..., object]]):
    """The registered rigs by id, each factory imported when it is asked for."""

    def __getitem__(self, name: str) -> Callable[..., object]:
        if name not in registry.rig_names():
            raise KeyError(name)
        return registry.rig(name)

    def __iter__(self) -> Iterator[str]:
        return iter(registry.rig_names())

    def __len__(self) -> int:
        return len(registry.rig_names())


RIGS: Mapping[str, Callable[..., object]] = _Registered()

__all__ = [
    "RIGS",
    "Align",
    "Conv1",
    "Conv2x2",
    "Conv3",
    "ConveyorLine",
    "HBW",
    "Machine",
    "Panel",
    "Punch",
    "Skip",
    "Slide",
    "Sort",
    "Spindle",
    "StationOccupiedError",
]
