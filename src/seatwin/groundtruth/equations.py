"""Ground-truth equations of thesis §3.3.2 as small pure functions (NED, metres, radians).

Eq. 3.6 (heading from the bow and stern antennas) is :func:`seatwin.geo.heading_from_antennas`.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from seatwin.geo import heading_from_antennas, wrap_to_pi

__all__ = [
    "antenna_midpoint",
    "antenna_distance",
    "course_over_ground",
    "gnss_baseline_error",
    "heading_from_antennas",
    "velocity_central",
]


def antenna_midpoint(
    north_bow: ArrayLike, east_bow: ArrayLike, north_stern: ArrayLike, east_stern: ArrayLike
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """The vessel position: the midpoint between the bow and stern antennas."""
    return (
        0.5 * (np.asarray(north_bow, float) + np.asarray(north_stern, float)),
        0.5 * (np.asarray(east_bow, float) + np.asarray(east_stern, float)),
    )


def antenna_distance(
    north_bow: ArrayLike, east_bow: ArrayLike, north_stern: ArrayLike, east_stern: ArrayLike
) -> NDArray[np.float64]:
    """Measured horizontal bow–stern antenna distance √((y_sb−y_ss)² + (x_sb−x_ss)²)."""
    return np.hypot(
        np.asarray(north_bow, float) - np.asarray(north_stern, float),
        np.asarray(east_bow, float) - np.asarray(east_stern, float),
    )


def gnss_baseline_error(
    north_bow: ArrayLike,
    east_bow: ArrayLike,
    north_stern: ArrayLike,
    east_stern: ArrayLike,
    baseline_m: float,
) -> NDArray[np.float64]:
    """ε_gnss = |√((y_sb−y_ss)² + (x_sb−x_ss)²) − |Q_r||, thesis eq. 3.7.

    ``baseline_m`` is the hand-measured antenna distance |Q_r| (thesis: Finn 2.93 m, Havfruen 2.01 m).
    """
    return np.abs(antenna_distance(north_bow, east_bow, north_stern, east_stern) - float(baseline_m))


def velocity_central(
    time: ArrayLike, north: ArrayLike, east: ArrayLike, window: int = 1
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """Velocity [m/s] by central differences (one-sided at the ends), then a centred moving
    average over ``window`` samples (odd; 1 = no smoothing; the window shrinks at the ends)."""
    t = np.asarray(time, float)
    v = [np.gradient(np.asarray(x, float), t) for x in (north, east)]
    if window > 1:
        half = window // 2
        kernel = np.ones(2 * half + 1)
        counts = np.convolve(np.ones(len(t)), kernel, mode="same")
        v = [np.convolve(x, kernel, mode="same") / counts for x in v]
    return v[0], v[1]


def course_over_ground(v_north: ArrayLike, v_east: ArrayLike) -> NDArray[np.float64]:
    """Course over ground atan2(v_east, v_north) ∈ [−π, π) [rad], clockwise from north."""
    return np.asarray(wrap_to_pi(np.arctan2(np.asarray(v_east, float), np.asarray(v_north, float))), float)
