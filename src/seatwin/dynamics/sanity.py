"""Physical sanity figures of a vessel model: top speed, turning circle, stopping distances (docs/validation.md).

Each manoeuvre is flown with the thrusters' rate limits through :func:`~seatwin.dynamics.integrate.step_thrusters`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

from seatwin.dynamics.integrate import VesselState, step_thrusters
from seatwin.dynamics.thrusters import MILLIAMPERE_THRUSTERS, ThrusterConfig, ThrusterState
from seatwin.dynamics.vessel import MILLIAMPERE, Model, VesselParameters


@dataclass(frozen=True)
class Manoeuvres:
    """The figures (SI units)."""

    top_speed: float
    """Steady surge speed at full thrust ahead [m/s]."""
    time_to_90pct: float
    """Seconds from rest to 90 % of the top speed."""
    turn_radius: float
    """Steady turning radius at full thrust with the azimuths at ±``turn_angle`` [m]."""
    turn_speed: float
    """Steady speed in that turn [m/s]."""
    turn_angle_deg: float
    coast_distance: float
    """From top speed, thrust off: distance until the speed is under 0.2 m/s [m]."""
    coast_time: float
    crash_stop_distance: float
    """From top speed, azimuths turned aft at their rate limit, full thrust: distance until the speed is under 0.05 m/s [m]."""
    crash_stop_time: float


def _fly(
    model: Model,
    th: ThrusterConfig,
    state: VesselState,
    angles: tuple[float, ...],
    thrust: tuple[float, ...],
    dt: float,
    t_max: float,
) -> list[VesselState]:
    out = [state]
    while state.time - out[0].time < t_max:
        state = step_thrusters(model, th, state, (angles, thrust), dt)
        out.append(state)
    return out


def manoeuvres(
    p: VesselParameters = MILLIAMPERE, th: ThrusterConfig = MILLIAMPERE_THRUSTERS, turn_angle_deg: float = 5.0, dt: float = 0.05
) -> Manoeuvres:
    """Fly the standard manoeuvres of ``p`` with thrusters ``th``."""
    model = Model(p)
    n = len(th.x)
    rest = VesselState(0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, ThrusterState.idle(n))
    full = tuple(th.max_thrust)
    run = _fly(model, th, rest, (0.0,) * n, full, dt, 300.0)
    top = run[-1].u
    t90 = next(s.time for s in run if s.u >= 0.9 * top)
    at_speed = replace(run[-1], time=0.0)
    a = math.radians(turn_angle_deg)
    angles = tuple(a if x > 0 else -a for x in th.x)  # fore thruster to starboard, aft to port: a starboard turn
    turn = _fly(model, th, at_speed, angles, full, dt, 300.0)[-1]
    radius = turn.speed / abs(turn.r) if turn.r else math.inf
    coast = _fly(model, th, at_speed, (0.0,) * n, (0.0,) * n, dt, 600.0)
    stop = next((s for s in coast if s.speed < 0.2), coast[-1])
    crash = _fly(model, th, at_speed, (math.pi - 1e-9,) * n, full, dt, 120.0)
    halt = next((s for s in crash if s.u < 0.05), crash[-1])
    return Manoeuvres(
        top_speed=top,
        time_to_90pct=t90,
        turn_radius=radius,
        turn_speed=turn.speed,
        turn_angle_deg=turn_angle_deg,
        coast_distance=math.hypot(stop.north - at_speed.north, stop.east - at_speed.east),
        coast_time=stop.time,
        crash_stop_distance=math.hypot(halt.north - at_speed.north, halt.east - at_speed.east),
        crash_stop_time=halt.time,
    )
