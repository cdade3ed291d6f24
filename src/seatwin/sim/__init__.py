"""The one simulation loop: every sensor at its own frame times, the world posed at each, recorded or kept in memory."""

from seatwin.sim.loop import SimulationResult, frames, simulate
from seatwin.sim.run import scenario_sensors, simulate_scenario
from seatwin.sim.sensors import GroundTruthSensor, LidarSensor, SimSensor
from seatwin.sim.settings import SimulationSettings

__all__ = [
    "GroundTruthSensor",
    "LidarSensor",
    "SimSensor",
    "SimulationResult",
    "SimulationSettings",
    "frames",
    "scenario_sensors",
    "simulate",
    "simulate_scenario",
]
