"""The one-clock loop: a controller, a plant, their wiring, the scenario and the recorder."""

from plcsim.sim.simulation import (
    Pacing,
    Realtime,
    RealtimeSimulation,
    Simulation,
    SimulationError,
)

__all__ = [
    "SimulationError",
    "Simulation",
    "Pacing",
    "Realtime",
    "RealtimeSimulation",
]
