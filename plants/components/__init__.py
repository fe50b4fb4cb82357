"""Reusable parts of the plant models: belt, light barrier, limit switch, workpiece, operator panel, side-view base."""

from plants.components.belt import Belt
from plants.components.light_barrier import LightBarrier
from plants.components.limit_switch import LimitSwitch
from plants.components.panel import OperatorPanel
from plants.components.side_view import DeadPlate, EndStop, SideViewPlant, StationOccupiedError
from plants.components.workpiece import STANDARD, Part, WorkpieceSpec

__all__ = [
    "Belt",
    "DeadPlate",
    "EndStop",
    "LightBarrier",
    "LimitSwitch",
    "OperatorPanel",
    "Part",
    "STANDARD",
    "SideViewPlant",
    "StationOccupiedError",
    "WorkpieceSpec",
]
