"""Headings: degree/radian at file boundaries, eq. 3.6 (wrapping is :mod:`seatwin.geo.angles`)."""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from seatwin.geo.angles import wrap_to_pi


def deg_to_rad_heading(deg: ArrayLike) -> NDArray[np.float64] | float:
    """Compass heading in degrees (clockwise from north) → radians in [−π, π)."""
    return wrap_to_pi(np.radians(np.asarray(deg, dtype=float)))


def rad_to_deg_heading(rad: ArrayLike) -> NDArray[np.float64] | float:
    """Heading in radians → degrees in [−180, 180) (the scenario CSV convention)."""
    d = np.degrees(np.asarray(wrap_to_pi(np.asarray(rad, dtype=float)), dtype=float))
    # wrap_to_pi can round to exactly π·(180/π)=180 for inputs a hair below π.
    d = np.where(d >= 180.0, d - 360.0, d)
    return float(d) if d.ndim == 0 else d


def heading_from_antennas(
    north_bow: ArrayLike, east_bow: ArrayLike, north_stern: ArrayLike, east_stern: ArrayLike
) -> NDArray[np.float64] | float:
    """Heading from bow and stern antenna positions in NED, thesis eq. 3.6.

    ψ = atan2(y_sb − y_ss, x_sb − x_ss) ∈ [−π, π), x north and y east.
    """
    de = np.asarray(east_bow, float) - np.asarray(east_stern, float)
    dn = np.asarray(north_bow, float) - np.asarray(north_stern, float)
    return wrap_to_pi(np.arctan2(de, dn))
