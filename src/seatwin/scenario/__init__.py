"""Scenarios: vessels, their trajectories, readers and writers, and the built-in scenarios."""

from seatwin.scenario.model import Dimensions, Role, Scenario, Trajectory, Vessel, VesselState

__all__ = ["Dimensions", "Role", "Scenario", "Trajectory", "Vessel", "VesselState"]
