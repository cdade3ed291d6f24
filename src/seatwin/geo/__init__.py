"""Geodesy, angles and frames: WGS-84, the thesis's flat-earth LLH↔NED, headings, rotations.

A leaf of the package: it imports nothing else of seatwin (checked by
``tests/geo/test_geo_leaf.py``), and raises plain :class:`ValueError` for bad values.
"""

from seatwin.geo.angles import TWO_PI, circular_mean, unwrap, wrap_to_2pi, wrap_to_180, wrap_to_pi
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
from seatwin.geo.frames import (
    AXES,
    FLU_TO_FRD,
    NED_TO_ENU,
    OPTICAL_TO_FRD,
    enu_to_ned,
    euler_zyx,
    mount_matrix,
    ned_to_enu,
    quaternion_matrix,
    rot_x,
    rot_y,
    rot_z,
    yaw_matrix,
    yaw_rotate,
)
from seatwin.geo.heading import deg_to_rad_heading, heading_from_antennas, rad_to_deg_heading
from seatwin.geo.wgs84 import WGS84_A, WGS84_E, WGS84_E2, WGS84_F

__all__ = [
    "AXES",
    "FLU_TO_FRD",
    "GeodeticOrigin",
    "NED_TO_ENU",
    "OPTICAL_TO_FRD",
    "TWO_PI",
    "WGS84_A",
    "WGS84_E",
    "WGS84_E2",
    "WGS84_F",
    "circular_mean",
    "deg_to_rad_heading",
    "enu_to_ned",
    "euler_zyx",
    "heading_from_antennas",
    "llh_to_ned_exact",
    "llh_to_ned_flat",
    "meridian_radius",
    "meridian_radius_printed",
    "mount_matrix",
    "ned_to_enu",
    "ned_to_llh_exact",
    "ned_to_llh_flat",
    "prime_vertical_radius",
    "quaternion_matrix",
    "rad_to_deg_heading",
    "rot_x",
    "rot_y",
    "rot_z",
    "unwrap",
    "wrap_to_180",
    "wrap_to_2pi",
    "wrap_to_pi",
    "yaw_matrix",
    "yaw_rotate",
]
