"""The vessel's state and one fixed step of it (classical 4th-order Runge–Kutta), deterministic and pure.

The thrusters move at the start of a step (rate limits, :func:`~seatwin.dynamics.thrusters.actuate`) and their force
is held through it; the rigid body (η, ν) is integrated with RK4 under that force.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

from seatwin.dynamics.thrusters import ThrusterConfig, ThrusterState, actuate, allocate, generalised_force
from seatwin.dynamics.vessel import Model, pose_rates
from seatwin.geo import wrap_to_pi


@dataclass(frozen=True)
class VesselState:
    """One vessel at one time: pose, body velocity and thrusters."""

    time: float
    north: float
    east: float
    heading: float
    """rad, clockwise from north"""
    u: float
    v: float
    r: float
    thrusters: ThrusterState

    @property
    def speed(self) -> float:
        return math.hypot(self.u, self.v)

    @property
    def course(self) -> float:
        """Course over ground [rad]."""
        return float(wrap_to_pi(self.heading + math.atan2(self.v, self.u))) if self.speed > 0 else self.heading

    @property
    def velocity_ne(self) -> tuple[float, float]:
        """World-frame velocity (north, east) [m/s]."""
        n, e, _ = pose_rates(self.heading, (self.u, self.v, self.r))
        return n, e


def rk4(model: Model, state: VesselState, tau: tuple[float, float, float], dt: float) -> VesselState:
    """η, ν after ``dt`` under a constant ``tau`` (the thrusters unchanged)."""

    def f(y: tuple[float, ...]) -> tuple[float, ...]:
        nu = (y[3], y[4], y[5])
        return (*pose_rates(y[2], nu), *model.accelerations(nu, tau))

    y0 = (state.north, state.east, state.heading, state.u, state.v, state.r)
    k1 = f(y0)
    k2 = f(tuple(a + 0.5 * dt * b for a, b in zip(y0, k1)))
    k3 = f(tuple(a + 0.5 * dt * b for a, b in zip(y0, k2)))
    k4 = f(tuple(a + dt * b for a, b in zip(y0, k3)))
    y = tuple(a + dt / 6.0 * (b1 + 2.0 * b2 + 2.0 * b3 + b4) for a, b1, b2, b3, b4 in zip(y0, k1, k2, k3, k4))
    return replace(state, time=state.time + dt, north=y[0], east=y[1], heading=float(wrap_to_pi(y[2])), u=y[3], v=y[4], r=y[5])


def step_thrusters(
    model: Model,
    thrusters: ThrusterConfig,
    state: VesselState,
    command: tuple[tuple[float, ...], tuple[float, ...]],
    dt: float,
) -> VesselState:
    """One step with thruster ``command`` = (azimuths, thrusts): the actuators move, then the hull."""
    th = actuate(thrusters, state.thrusters, command[0], command[1], dt)
    return rk4(model, replace(state, thrusters=th), generalised_force(thrusters, th), dt)


def step_force(
    model: Model,
    thrusters: ThrusterConfig,
    state: VesselState,
    tau: tuple[float, float, float],
    dt: float,
    cone: float | None = None,
) -> VesselState:
    """One step with a desired generalised force ``tau`` (allocated to the thrusters first; ``cone`` as
    :func:`~seatwin.dynamics.thrusters.allocate`)."""
    return step_thrusters(model, thrusters, state, allocate(thrusters, tau, state.thrusters, cone), dt)
