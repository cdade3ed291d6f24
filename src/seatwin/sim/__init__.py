"""The stepping loop: every sensor at its own rate and phase, the world posed at each sensor time, recorded."""

from seatwin.sim.loop import SimulationResult, simulate
from seatwin.sim.run import simulate_scenario
from seatwin.sim.sensors import GroundTruthSensor, LidarSensor, SimSensor

__all__ = ["GroundTruthSensor", "LidarSensor", "SimSensor", "SimulationResult", "simulate", "simulate_scenario"]
