"""Vessel dynamics (pure, like :mod:`seatwin.geo`): the 3-DOF manoeuvring model with milliAmpere's identified
parameters, azimuth thrusters with allocation and rate limits, a fixed-step RK4 integrator, a speed/heading
autopilot, and waypoint-following targets.

* :mod:`.vessel` — :class:`VesselParameters`, :data:`MILLIAMPERE`, M ν̇ + C(ν)ν + D(ν)ν = τ;
* :mod:`.thrusters` — :data:`MILLIAMPERE_THRUSTERS`, :func:`allocate`, :func:`actuate`;
* :mod:`.integrate` — :class:`VesselState`, :func:`step_force`, :func:`step_thrusters` (RK4);
* :mod:`.control` — :class:`Autopilot` (speed, heading → τ);
* :mod:`.targets` — :func:`follow_waypoints` (kinematic LOS waypoint follower);
* :mod:`.sanity` — top speed, turning circle, stopping distance of a model.
"""

from seatwin.dynamics.control import Autopilot
from seatwin.dynamics.integrate import VesselState, rk4, step_force, step_thrusters
from seatwin.dynamics.targets import WaypointPath, follow_waypoints
from seatwin.dynamics.thrusters import (
    MILLIAMPERE_THRUSTERS,
    ThrusterConfig,
    ThrusterState,
    actuate,
    allocate,
    generalised_force,
)
from seatwin.dynamics.vessel import MILLIAMPERE, Model, VesselParameters, pose_rates

__all__ = [
    "MILLIAMPERE",
    "MILLIAMPERE_THRUSTERS",
    "Autopilot",
    "Model",
    "ThrusterConfig",
    "ThrusterState",
    "VesselParameters",
    "VesselState",
    "WaypointPath",
    "actuate",
    "allocate",
    "follow_waypoints",
    "generalised_force",
    "pose_rates",
    "rk4",
    "step_force",
    "step_thrusters",
]
