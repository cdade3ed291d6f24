"""Sensor poses in the world: ownship pose (north, east, heading) ∘ sensor mount (body frame).

A mount is the pose of the sensor frame in the vessel body frame (x forward, y starboard,
z down), as recorded on /tf_static: translation [m] and quaternion (x, y, z, w). The ownship
pose has only a heading (roll and pitch are not in the ground truth), so body → world is a
rotation about the down axis.
"""

from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from seatwin.geo.frames import FLU_TO_FRD, quaternion_matrix, yaw_matrix

Array = NDArray[np.float64]


@dataclass(frozen=True)
class Mount:
    """Pose of a sensor in the body frame: ``p_body = rotation @ p_sensor + translation``."""

    translation: tuple[float, float, float] = (0.0, 0.0, 0.0)
    rotation: Array = field(default_factory=FLU_TO_FRD.copy)

    @classmethod
    def from_quaternion(cls, translation: ArrayLike, q: ArrayLike) -> Mount:
        return cls(tuple(float(v) for v in np.asarray(translation, float)), quaternion_matrix(q))


@dataclass(frozen=True)
class SensorPose:
    """Where a sensor is in the world at one time: ``p_world = rotation @ p_sensor + position``."""

    position: Array
    """(3,) north, east, down of the sensor origin."""
    rotation: Array
    """(3, 3) sensor frame → world NED."""
    body_rotation: Array
    """(3, 3) body → world (the ownship heading)."""
    ownship_position: Array
    """(3,) the ownship reference point."""

    @property
    def north(self) -> float:
        return float(self.position[0])

    @property
    def east(self) -> float:
        return float(self.position[1])

    def to_world(self, points: Array) -> Array:
        """(N, 3) sensor-frame points → world NED."""
        return points @ self.rotation.T + self.position

    def to_body(self, world: Array) -> Array:
        """(N, 3) world points → the ownship body frame (about its reference point)."""
        return (world - self.ownship_position) @ self.body_rotation

    @property
    def boresight_bearing(self) -> float:
        """World bearing of the sensor's x axis (clockwise from north)."""
        fwd = self.rotation[:, 0]
        return float(np.arctan2(fwd[1], fwd[0]))


def sensor_pose(north: float, east: float, heading: float, mount: Mount | None = None, down: float = 0.0) -> SensorPose:
    """The sensor pose for an ownship at (north, east, down) with ``heading`` and a sensor ``mount``."""
    mount = mount or Mount()
    Rb = yaw_matrix(heading)
    own = np.array([north, east, down], dtype=float)
    return SensorPose(own + Rb @ np.asarray(mount.translation, float), Rb @ mount.rotation, Rb, own)


def recording_mounts(static_transforms: Iterable[Any]) -> dict[str, Mount]:
    """Every frame's mount in its vessel's FRD body frame from a recording's /tf_static
    (:func:`seatwin.recording.tf_tree.body_mounts`: REP-105 trees and older recordings alike)."""
    from seatwin.recording.tf_tree import body_mounts

    return {f: Mount(tuple(float(v) for v in m.translation), m.rotation) for f, m in body_mounts(static_transforms).items()}  # type: ignore[arg-type]
