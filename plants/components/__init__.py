"""Reusable parts of the plant models on the component protocol (``component.py``): the side-view base with its
axis, belt, light barrier, limit switch, end stop and dead plate; the top-view base with its belt, beams and spot
sensors, colour sensor, pistons, compressor, fences and bins; the workpiece and the operator panel. A rig of one's own
is one class built from them (``docs/writing-a-rig.md``)."""

from plants.components.axis import Axis
from plants.components.belt import Belt
from plants.components.bins import Bins
from plants.components.colour_sensor import ColourSensor
from plants.components.component import Assembly, Bench, Carrier, Component, Host, ZoneSensor, zone
from plants.components.compressor import Compressor
from plants.components.frame import DeadPlate, EndStop
from plants.components.light_barrier import LightBarrier
from plants.components.limit_switch import LimitSwitch
from plants.components.panel import OperatorPanel
from plants.components.piston import Piston
from plants.components.side_view import SideViewPlant, StationOccupiedError
from plants.components.top_belt import TopBelt
from plants.components.top_view import Beam, Fence, SpotSensor, TopViewPlant
from plants.components.workpiece import STANDARD, Part, WorkpieceSpec

__all__ = [
    "Assembly",
    "Axis",
    "Bench",
    "Component",
    "Host",
    "Carrier",
    "ZoneSensor",
    "zone",
    "Beam",
    "Bins",
    "ColourSensor",
    "Compressor",
    "Fence",
    "Piston",
    "SpotSensor",
    "TopBelt",
    "TopViewPlant",
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
