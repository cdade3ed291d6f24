"""WGS-84 ellipsoid constants."""

WGS84_A = 6_378_137.0
"""Equatorial radius r_e [m]."""
WGS84_F = 1.0 / 298.257223563
"""Flattening."""
WGS84_E2 = WGS84_F * (2.0 - WGS84_F)
"""First eccentricity squared e² (the thesis rounds e to 0.0818)."""
WGS84_E = WGS84_E2**0.5
