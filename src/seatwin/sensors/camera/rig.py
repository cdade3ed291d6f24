"""The camera rig on the ownship: mounts (REP-103/105 optical frames), poses in the world, CameraInfo fields.

A camera's optical frame (z forward along the optical axis, x right, y down) sits in the vessel
body frame (FRD) at ``(mount_x, mount_y, −height)``, turned by its azimuth (yaw to starboard)
and pitched down (:func:`seatwin.geo.mount_matrix` with the ``optical`` axes):
``v_body = R_mount @ v_optical``. In the world (NED) at ownship heading ψ:
``R_world = yaw_matrix(ψ) @ R_mount``, centre ``(n, e, 0) + yaw_matrix(ψ) @ t_mount``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from seatwin.geo import mount_matrix, yaw_matrix
from seatwin.sensors.camera.config import CameraConfig
from seatwin.sensors.camera.intrinsics import intrinsic_matrix


@dataclass(frozen=True)
class CameraMount:
    """One camera of the rig: its name, optical frame id and pose in the vessel body frame (FRD)."""

    name: str
    frame_id: str
    translation: tuple[float, float, float]
    rotation: NDArray[np.float64]
    """Optical → body rotation (``v_body = rotation @ v_optical``)."""
    azimuth_deg: float

    def world_pose(self, north: float, east: float, heading: float) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
        """(optical → world rotation, centre in world NED) for the ownship at (north, east, heading)."""
        yaw = yaw_matrix(heading)
        return yaw @ self.rotation, np.array([north, east, 0.0]) + yaw @ np.asarray(self.translation, float)

    def axis_bearing(self, heading: float) -> float:
        """World bearing [rad, clockwise from north] of the optical axis' horizontal direction."""
        return heading + math.radians(self.azimuth_deg)


def optical_frame(name: str) -> str:
    """The optical frame id of camera ``name`` (REP-103 ``_optical_frame`` suffix)."""
    return f"camera_{name}_optical_frame"


def rig_mounts(config: CameraConfig) -> list[CameraMount]:
    """Every camera of ``config`` mounted on the rig (thesis 3.2.1: 72° apart, front along the bow, 15° down)."""
    out = []
    for name, az in zip(config.names, config.azimuths_deg, strict=True):
        r = mount_matrix("optical", pitch=-math.radians(config.pitch_down_deg), yaw=math.radians(az))
        out.append(CameraMount(name, optical_frame(name), (config.mount_x_m, config.mount_y_m, -config.height_m), r, float(az)))
    return out


@dataclass(frozen=True)
class CameraInfoFields:
    """``sensor_msgs/CameraInfo`` of a rig camera: plumb-bob ``D`` (5), ``K``, ``R`` = I, ``P`` = [K | 0]."""

    width: int
    height: int
    k: NDArray[np.float64]
    d: tuple[float, ...]
    r: NDArray[np.float64]
    p: NDArray[np.float64]
    distortion_model: str = "plumb_bob"


def camera_info_fields(config: CameraConfig) -> CameraInfoFields:
    """The CameraInfo every camera of ``config`` records (one set of intrinsics for the rig)."""
    k = intrinsic_matrix(config.width, config.height, config.hfov_deg)
    p = np.zeros((3, 4))
    p[:, :3] = k
    return CameraInfoFields(config.width, config.height, k, tuple(float(x) for x in config.distortion), np.eye(3), p)
