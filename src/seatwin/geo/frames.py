"""Frames and rotations: NED ↔ ENU, FLU ↔ FRD, yaw, roll/pitch/yaw mounts, quaternions.

Conventions (``docs/architecture.md``): the world is local NED (x north, y east, z down);
a vessel body is FRD (x forward, y starboard, z down); sensor data leave in REP-103 FLU
(x forward, y left, z up); cameras in the optical frame (z forward, x right, y down).
A rotation matrix ``R`` maps coordinates in the child frame to the parent: ``v_parent = R @ v_child``.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

Matrix = NDArray[np.float64]

FLU_TO_FRD: Matrix = np.diag([1.0, -1.0, -1.0])
"""A FLU frame (x forward, y left, z up) seen in a FRD frame with the same x: a half turn about
x. Its own inverse, so it also maps FRD → FLU (and ENU-style z-up meshes → z-down)."""

OPTICAL_TO_FRD: Matrix = np.array([[0.0, 0.0, 1.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]])
"""A camera optical frame (z forward, x right, y down) looking along the FRD x axis."""

NED_TO_ENU: Matrix = np.array([[0.0, 1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, -1.0]])
"""Maps NED coordinates to ENU (swap north and east, negate down); its own inverse. As a
pose it is the rotation of a NED frame in the ENU frame above it."""

AXES: dict[str, Matrix] = {"flu": FLU_TO_FRD, "frd": np.eye(3), "optical": OPTICAL_TO_FRD}
"""Sensor axis conventions → their rotation into a FRD frame with the same forward direction."""


def ned_to_enu(v: ArrayLike) -> Matrix:
    """(…, 3) NED vectors → ENU."""
    a = np.asarray(v, dtype=float)
    return np.stack([a[..., 1], a[..., 0], -a[..., 2]], axis=-1)


def enu_to_ned(v: ArrayLike) -> Matrix:
    """(…, 3) ENU vectors → NED (the same swap: the map is its own inverse)."""
    return ned_to_enu(v)


def rot_x(angle: float) -> Matrix:
    """Rotation by ``angle`` [rad] about x (right-handed)."""
    c, s = np.cos(angle), np.sin(angle)
    return np.array([[1.0, 0.0, 0.0], [0.0, c, -s], [0.0, s, c]])


def rot_y(angle: float) -> Matrix:
    """Rotation by ``angle`` [rad] about y (in FRD: positive pitches the x axis up)."""
    c, s = np.cos(angle), np.sin(angle)
    return np.array([[c, 0.0, s], [0.0, 1.0, 0.0], [-s, 0.0, c]])


def yaw_matrix(heading: float) -> Matrix:
    """Rotation by ``heading`` [rad] about z: in NED/FRD (z down) clockwise seen from above, so
    it maps a body FRD frame to world NED for a vessel with that heading (clockwise from north)."""
    c, s = np.cos(heading), np.sin(heading)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


rot_z = yaw_matrix


def yaw_rotate(heading: ArrayLike, x: ArrayLike, y: ArrayLike) -> tuple[Matrix, Matrix]:
    """``(x, y)`` turned by ``heading`` [rad] about z, element-wise (one heading per point):
    the first two rows of ``yaw_matrix(heading) @ (x, y, ·)``, e.g. body (forward, starboard)
    → world (north, east) offsets."""
    c, s = np.cos(heading), np.sin(heading)
    return c * np.asarray(x) - s * np.asarray(y), s * np.asarray(x) + c * np.asarray(y)


def euler_zyx(roll: float = 0.0, pitch: float = 0.0, yaw: float = 0.0) -> Matrix:
    """``R_z(yaw) R_y(pitch) R_x(roll)``: turned by yaw, then pitched, then rolled about its own axes."""
    return yaw_matrix(yaw) @ rot_y(pitch) @ rot_x(roll)


def mount_matrix(axes: str = "flu", roll: float = 0.0, pitch: float = 0.0, yaw: float = 0.0) -> Matrix:
    """Rotation of a sensor frame in the vessel body frame (FRD): ``v_body = R @ v_sensor``.

    The sensor is turned by ``yaw`` (to starboard), ``pitch`` (nose up) and ``roll`` (starboard
    down) — Z-Y-X Euler angles [rad] in the body frame — and its axes follow ``axes``
    (:data:`AXES`: ``flu`` lidar/radar, ``optical`` camera, ``frd``).
    """
    if axes not in AXES:
        raise ValueError(f"unknown frame convention {axes!r}; expected one of {sorted(AXES)}")
    return euler_zyx(roll, pitch, yaw) @ AXES[axes]


def quaternion_matrix(q: ArrayLike) -> Matrix:
    """Rotation matrix of a quaternion (x, y, z, w), normalised first."""
    x, y, z, w = np.asarray(q, dtype=float) / np.linalg.norm(q)
    return np.array(
        [
            [1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
            [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
            [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)],
        ]
    )
