"""Geodesy: WGS-84, the thesis's flat-earth LLH↔NED conversion, headings."""

from seatwin.geo.flat_earth import (
    GeodeticOrigin,
    llh_to_ned_exact,
    llh_to_ned_flat,
    meridian_radius,
    meridian_radius_printed,
    ned_to_llh_exact,
    ned_to_llh_flat,
    prime_vertical_radius,
)
from seatwin.geo.heading import (
    deg_to_rad_heading,
    heading_from_antennas,
    rad_to_deg_heading,
    unwrap,
    wrap_to_pi,
)
from seatwin.geo.wgs84 import WGS84_A, WGS84_E, WGS84_E2, WGS84_F

__all__ = [
    "GeodeticOrigin",
    "WGS84_A",
    "WGS84_E",
    "WGS84_E2",
    "WGS84_F",
    "deg_to_rad_heading",
    "heading_from_antennas",
    "llh_to_ned_exact",
    "llh_to_ned_flat",
    "meridian_radius",
    "meridian_radius_printed",
    "ned_to_llh_exact",
    "ned_to_llh_flat",
    "prime_vertical_radius",
    "rad_to_deg_heading",
    "unwrap",
    "wrap_to_pi",
]
