"""Reusable parts of the plant models on the component protocol (``component.py``): axis, belt, light barrier,
limit switch, workpiece, operator panel, end stop and dead plate, the side-view base."""

from plants.components.axis import Axis
from plants.components.belt import Belt
from plants.components.component import Assembly, Bench, Component, Host
from plants.components.frame import DeadPlate, EndStop
from plants.components.light_barrier import LightBarrier
from plants.components.limit_switch import LimitSwitch
from plants.components.panel import OperatorPanel
from plants.components.side_view import SideViewPlant, StationOccupiedError
from plants.components.workpiece import STANDARD, Part, WorkpieceSpec

__all__ = [
    "Assembly",
    "Axis",
    "Bench",
    "Component",
    "Host",
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
