"""LLH ↔ local NED: the thesis's flat-earth formulas (eqs. 3.2–3.5) and the exact reference.

The flat-earth conversion is the MSS toolbox's ``llh2flat``/``flat2llh``. Eq. 3.5 as printed
in the thesis, R_M = R_N (1−e²)/√(1−e² sin² x₀), is wrong: the meridian radius is
R_M = R_N (1−e²)/(1−e² sin² x₀) = r_e (1−e²)/(1−e² sin² x₀)^{3/2}. The correct form is the
default; the printed one is kept as ``meridian="printed"`` for reproducing the thesis.

Measured against the exact conversion (``pymap3d``, WGS-84) at 63.43° N, 10.39° E, h = 0:
horizontal error of the flat-earth NED of a point whose exact NED is at the given horizontal
distance (down = 0), worst of eight bearings (``tests/geo/test_flat_earth.py`` recomputes these):

=========  ===================  ========================
distance   correct R_M (3.5')   printed R_M (3.5)
=========  ===================  ========================
100 m      0.0017 m             0.27 m
1 km       0.17 m               2.7 m
5 km       4.4 m                13.4 m
=========  ===================  ========================

(The correct-R_M error grows with the square of the distance and comes from the convergence
of meridians: a parallel is not a straight line in the tangent plane, so at 5 km due east the
flat-earth north is 3.9 m off, ≈ d² tan x₀ / 2R, and at 45° the east is 3.9 m off. The printed
eq. 3.5 adds a north–south scale error of 1 − √(1 − e² sin² x₀) ≈ e² sin² x₀ / 2 ≈ 2.7 ‰ at
63.43° N, which dominates up to several kilometres.)
"""

from __future__ import annotations

from dataclasses import dataclass
from typing import Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray

from seatwin.geo.angles import wrap_to_180
from seatwin.geo.wgs84 import WGS84_A, WGS84_E2

Meridian = Literal["correct", "printed"]


@dataclass(frozen=True)
class GeodeticOrigin:
    """The geodetic origin of a local NED frame (degrees, metres); :class:`ValueError` if out of range."""

    lat_deg: float
    lon_deg: float
    height_m: float = 0.0

    def __post_init__(self) -> None:
        if not np.isfinite([self.lat_deg, self.lon_deg, self.height_m]).all():
            raise ValueError(f"latitude, longitude and height must be finite, got {self}")
        if not -90.0 <= self.lat_deg <= 90.0:
            raise ValueError(f"latitude must be in [-90, 90] degrees, got {self.lat_deg}")
        if not -180.0 <= self.lon_deg <= 360.0:
            raise ValueError(f"longitude must be in [-180, 360] degrees, got {self.lon_deg}")


def prime_vertical_radius(lat0_rad: float) -> float:
    """R_N = r_e / √(1 − e² sin² x₀), thesis eq. 3.4."""
    return WGS84_A / np.sqrt(1.0 - WGS84_E2 * np.sin(lat0_rad) ** 2)


def meridian_radius(lat0_rad: float) -> float:
    """R_M = R_N (1 − e²)/(1 − e² sin² x₀) — the correct form of thesis eq. 3.5 (as in MSS)."""
    return prime_vertical_radius(lat0_rad) * (1.0 - WGS84_E2) / (1.0 - WGS84_E2 * np.sin(lat0_rad) ** 2)


def meridian_radius_printed(lat0_rad: float) -> float:
    """R_M = R_N (1 − e²)/√(1 − e² sin² x₀) — thesis eq. 3.5 exactly as printed (wrong; for reproduction)."""
    return prime_vertical_radius(lat0_rad) * (1.0 - WGS84_E2) / np.sqrt(1.0 - WGS84_E2 * np.sin(lat0_rad) ** 2)


def _radii(origin: GeodeticOrigin, meridian: Meridian) -> tuple[float, float]:
    lat0 = np.radians(origin.lat_deg)
    if meridian == "correct":
        r_m = meridian_radius(lat0)
    elif meridian == "printed":
        r_m = meridian_radius_printed(lat0)
    else:
        raise ValueError(f"meridian must be 'correct' or 'printed', got {meridian!r}")
    return r_m, prime_vertical_radius(lat0)


def llh_to_ned_flat(
    lat_deg: ArrayLike,
    lon_deg: ArrayLike,
    height_m: ArrayLike,
    origin: GeodeticOrigin,
    meridian: Meridian = "correct",
) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
    """Flat-earth LLH → NED, thesis eqs. 3.2 (north) and 3.3 (east); down = −(h − h₀)."""
    r_m, r_n = _radii(origin, meridian)
    dlat = np.radians(np.asarray(lat_deg, float) - origin.lat_deg)
    # Longitude difference wrapped to [−180°, 180°) so points across the antimeridian stay near.
    dlon = np.radians(wrap_to_180(np.asarray(lon_deg, float) - origin.lon_deg))
    north = dlat / np.arctan2(1.0, r_m)
    east = dlon / np.arctan2(1.0, r_n * np.cos(np.radians(origin.lat_deg)))
    down = -(np.asarray(height_m, float) - origin.height_m)
    return north, east, down


def ned_to_llh_flat(
    north: ArrayLike,
    east: ArrayLike,
    down: ArrayLike,
    origin: GeodeticOrigin,
    meridian: Meridian = "correct",
) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
    """Inverse of :func:`llh_to_ned_flat` (MSS ``flat2llh``)."""
    r_m, r_n = _radii(origin, meridian)
    lat = origin.lat_deg + np.degrees(np.asarray(north, float) * np.arctan2(1.0, r_m))
    lon = origin.lon_deg + np.degrees(np.asarray(east, float) * np.arctan2(1.0, r_n * np.cos(np.radians(origin.lat_deg))))
    height = origin.height_m - np.asarray(down, float)
    return lat, lon, height


def llh_to_ned_exact(
    lat_deg: ArrayLike, lon_deg: ArrayLike, height_m: ArrayLike, origin: GeodeticOrigin
) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
    """Exact LLH → NED on WGS-84 (through ECEF, ``pymap3d``): the reference for the flat-earth form."""
    import pymap3d  # 0.15 s to import: only where the exact conversion is used

    n, e, d = pymap3d.geodetic2ned(
        np.asarray(lat_deg, float),
        np.asarray(lon_deg, float),
        np.asarray(height_m, float),
        origin.lat_deg,
        origin.lon_deg,
        origin.height_m,
    )
    return np.asarray(n, float), np.asarray(e, float), np.asarray(d, float)


def ned_to_llh_exact(
    north: ArrayLike, east: ArrayLike, down: ArrayLike, origin: GeodeticOrigin
) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
    """Exact NED → LLH on WGS-84 (``pymap3d``)."""
    import pymap3d

    lat, lon, h = pymap3d.ned2geodetic(
        np.asarray(north, float),
        np.asarray(east, float),
        np.asarray(down, float),
        origin.lat_deg,
        origin.lon_deg,
        origin.height_m,
    )
    return np.asarray(lat, float), np.asarray(lon, float), np.asarray(h, float)
