"""Exact NED → WGS-84 geodetic, vectorised, without ``pymap3d``'s per-call overhead.

:func:`ned_to_llh_wgs84` is ``pymap3d.ned2geodetic`` (ENU → ECEF about the origin, then You's
closed-form ECEF → geodetic, *J. Surv. Eng.* 2000) written out operation for operation on numpy
arrays, with the origin's terms computed once per origin: the same floating-point operations in
the same order, so the same bits as :func:`seatwin.geo.ned_to_llh_exact` (checked by
``tests/geo/test_geodetic.py``), at ~30 µs for one point instead of ~200 µs. The two degenerate
cases ``pymap3d`` patches (a point at the Earth's centre or on its axis) go to ``pymap3d`` itself.
"""

from __future__ import annotations

import math
from functools import lru_cache

import numpy as np
from numpy.typing import ArrayLike, NDArray

from seatwin.geo.flat_earth import GeodeticOrigin, ned_to_llh_exact

_A = 6378137.0
_B = 6356752.31424518
"""WGS-84 semi-axes as ``pymap3d`` spells them (``Ellipsoid.from_name("wgs84")``): the same bits."""
_E = math.sqrt(_A**2 - _B**2)
_LIM_PI2 = math.pi / 2 - float(np.finfo(np.float64).eps)


@lru_cache(maxsize=16)
def _origin_terms(lat_deg: float, lon_deg: float, h_m: float) -> tuple[np.float64, ...]:
    """(x0, y0, z0, cos lat0, sin lat0, cos lon0, sin lon0) as ``pymap3d.enu2ecef`` computes them."""
    lat, lon = np.radians(lat_deg), np.radians(lon_deg)
    n = _A**2 / np.hypot(_A * np.cos(lat), _B * np.sin(lat))
    x0 = (n + h_m) * np.cos(lat) * np.cos(lon)
    y0 = (n + h_m) * np.cos(lat) * np.sin(lon)
    z0 = (n * (_B / _A) ** 2 + h_m) * np.sin(lat)
    return x0, y0, z0, np.cos(lat), np.sin(lat), np.cos(lon), np.sin(lon)


def ned_to_llh_wgs84(
    north: ArrayLike, east: ArrayLike, down: ArrayLike, origin: GeodeticOrigin
) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64]]:
    """Exact NED [m] about ``origin`` → (latitude °, longitude °, height m) on WGS-84; arrays like the inputs."""
    n, e, d = (np.asarray(a, dtype=np.float64) for a in (north, east, down))
    x0, y0, z0, clat, slat, clon, slon = _origin_terms(float(origin.lat_deg), float(origin.lon_deg), float(origin.height_m))
    up = -d
    t = clat * up - slat * n
    w = slat * up + clat * n
    x = x0 + (clon * t - slon * e)
    y = y0 + (slon * t + clon * e)
    z = z0 + w
    r = np.sqrt(x**2 + y**2 + z**2)
    u = np.sqrt(0.5 * (r**2 - _E**2) + 0.5 * np.hypot(r**2 - _E**2, 2 * _E * z))
    hxy = np.hypot(x, y)
    if (np.abs(u) <= 1e-8).any() or (np.abs(hxy) <= 1e-8).any():  # pymap3d's isclose(·, 0) patches
        return ned_to_llh_exact(n, e, d, origin)
    hue = np.hypot(u, _E)
    beta = np.arctan(hue / u * z / hxy)
    beta = beta + ((_B * u - _A * hue + _E**2) * np.sin(beta)) / (_A * hue * 1 / np.cos(beta) - _E**2 * np.cos(beta))
    lat = np.arctan(_A / _B * np.tan(beta))
    lon = np.arctan2(y, x)
    cos_beta = np.cos(beta)
    if (np.abs(beta) >= _LIM_PI2).any():  # pymap3d's patch of a pole for float32 precision loss
        lat = np.where(beta >= _LIM_PI2, np.pi / 2, lat)
        lat = np.where(beta <= -_LIM_PI2, -np.pi / 2, lat)
        cos_beta = np.where(beta >= _LIM_PI2, 0, cos_beta)
        cos_beta = np.where(beta <= -_LIM_PI2, 0, cos_beta)
    alt = np.hypot(z - _B * np.sin(beta), hxy - _A * cos_beta)
    inside = x**2 / _A**2 + y**2 / _A**2 + z**2 / _B**2 < 1
    alt = np.where(inside, -alt, alt)
    return np.degrees(lat), np.degrees(lon), alt
