"""Target vessels that follow waypoints: a kinematic model (constant speed, turn rate limited, line-of-sight
guidance), integrated on a fixed step into a trajectory (time, north, east, heading).

The heading turns towards the line-of-sight bearing to a point ``lookahead`` metres ahead along the current leg
(Fossen 2011, §10.3.2, lookahead-based LOS steering) at most ``max_turn_rate``; a waypoint within
``acceptance`` metres (or passed along its leg) switches to the next leg. Straight legs flown from their start on
their course come out exactly straight.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from seatwin.errors import ParameterError
from seatwin.geo import wrap_to_pi


@dataclass(frozen=True)
class WaypointPath:
    """Samples of a waypoint follower's path."""

    time: NDArray[np.float64]
    north: NDArray[np.float64]
    east: NDArray[np.float64]
    heading: NDArray[np.float64]


def follow_waypoints(
    waypoints: NDArray[np.float64] | list[tuple[float, float]],
    speed: float,
    start_time: float,
    duration: float,
    dt: float = 0.1,
    max_turn_rate: float = math.radians(5.0),
    lookahead: float = 20.0,
    acceptance: float = 5.0,
) -> WaypointPath:
    """Sail ``waypoints`` ((K ≥ 2, 2) north, east) at ``speed`` [m/s] from ``start_time`` for ``duration`` seconds;
    after the last waypoint the vessel keeps its last course."""
    wp = np.asarray(waypoints, dtype=float).reshape(-1, 2)
    if wp.shape[0] < 2 or not np.isfinite(wp).all():
        raise ParameterError("waypoints", f"expected at least 2 finite (north, east) waypoints, got {wp.tolist()}")
    if not (speed >= 0 and math.isfinite(speed)):
        raise ParameterError("speed", f"expected a speed ≥ 0, got {speed}")
    if not (dt > 0 and duration > 0):
        raise ParameterError("dt", f"expected dt > 0 and duration > 0, got {dt}, {duration}")
    n_steps = int(round(duration / dt))
    t = start_time + dt * np.arange(n_steps + 1)
    north, east, heading = np.empty(n_steps + 1), np.empty(n_steps + 1), np.empty(n_steps + 1)
    x, y = float(wp[0, 0]), float(wp[0, 1])
    psi = math.atan2(wp[1, 1] - wp[0, 1], wp[1, 0] - wp[0, 0])
    leg = 0
    for k in range(n_steps + 1):
        north[k], east[k], heading[k] = x, y, psi
        if k == n_steps:
            break
        # advance the leg when its end waypoint is reached or passed
        while leg < len(wp) - 2:
            a, b = wp[leg], wp[leg + 1]
            d = b - a
            along = ((x - a[0]) * d[0] + (y - a[1]) * d[1]) / max(float(d @ d), 1e-12)
            if math.hypot(b[0] - x, b[1] - y) <= acceptance or along >= 1.0:
                leg += 1
            else:
                break
        a, b = wp[leg], wp[leg + 1]
        course = math.atan2(b[1] - a[1], b[0] - a[0])
        # cross-track error (positive to starboard of the leg) and the LOS heading
        cross = -(x - a[0]) * math.sin(course) + (y - a[1]) * math.cos(course)
        desired = course - math.atan2(cross, lookahead)
        turn = float(wrap_to_pi(desired - psi))
        lim = max_turn_rate * dt
        psi = float(wrap_to_pi(psi + max(-lim, min(lim, turn))))
        x += speed * dt * math.cos(psi)
        y += speed * dt * math.sin(psi)
    return WaypointPath(t, north, east, heading)
