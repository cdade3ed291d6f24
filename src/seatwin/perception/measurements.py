"""Measurement types: what perception hands the tracker, one :class:`Scan` per sensor sweep.

All measurements are in the world frame (local NED) relative to the sensor position at the
scan time: a sensor-frame bearing is rotated by the ownship heading before it gets here.

* ``range_bearing`` (lidar clusters, radar plots): ``z = [range m, bearing rad]``, bearing
  clockwise from north, ``atan2(east, north)`` of the sensor-to-target vector.
* ``bearing`` (camera detections): ``z = [bearing rad]``, same convention.
* ``cartesian`` (plots given as positions): ``z = [north m, east m]``.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from enum import Enum

import numpy as np
from numpy.typing import ArrayLike, NDArray

from seatwin.geo import wrap_to_pi


class MeasurementKind(str, Enum):
    RANGE_BEARING = "range_bearing"
    BEARING = "bearing"
    CARTESIAN = "cartesian"

    @property
    def dim(self) -> int:
        """Length of one measurement vector."""
        return {"range_bearing": 2, "bearing": 1, "cartesian": 2}[self.value]


@dataclass(frozen=True)
class Scan:
    """One sensor sweep: its time, the sensor position in the world, and its measurements."""

    time: float
    """POSIX seconds."""
    sensor: str
    """Sensor name, e.g. ``lidar``, ``radar``, ``camera``; selects the tuning of the sensor."""
    kind: MeasurementKind
    z: NDArray[np.float64]
    """(M, kind.dim) measurements, world frame (see module docstring)."""
    sensor_north: float = 0.0
    sensor_east: float = 0.0
    extra: dict = field(default_factory=dict, compare=False)

    def __post_init__(self) -> None:
        kind = MeasurementKind(self.kind)
        object.__setattr__(self, "kind", kind)
        object.__setattr__(self, "z", np.asarray(self.z, dtype=float).reshape(-1, kind.dim))

    @property
    def sensor_position(self) -> NDArray[np.float64]:
        return np.array([self.sensor_north, self.sensor_east])

    def positions(self) -> NDArray[np.float64]:
        """(M, 2) north/east of the measurements (not defined for bearing-only scans)."""
        if self.kind is MeasurementKind.CARTESIAN:
            return self.z.copy()
        if self.kind is MeasurementKind.RANGE_BEARING:
            return polar_to_cartesian(self.z, self.sensor_position)
        raise ValueError("a bearing-only measurement has no position")


def polar_to_cartesian(z: ArrayLike, sensor: ArrayLike = (0.0, 0.0)) -> NDArray[np.float64]:
    """(M, 2) ``[range, bearing]`` about ``sensor`` → (M, 2) ``[north, east]``."""
    z = np.asarray(z, dtype=float).reshape(-1, 2)
    s = np.asarray(sensor, dtype=float)
    return np.column_stack((s[0] + z[:, 0] * np.cos(z[:, 1]), s[1] + z[:, 0] * np.sin(z[:, 1])))


def cartesian_to_polar(p: ArrayLike, sensor: ArrayLike = (0.0, 0.0)) -> NDArray[np.float64]:
    """(M, 2) ``[north, east]`` → (M, 2) ``[range, bearing]`` about ``sensor`` (bearing in [−π, π))."""
    p = np.asarray(p, dtype=float).reshape(-1, 2)
    s = np.asarray(sensor, dtype=float)
    d = p - s
    return np.column_stack((np.hypot(d[:, 0], d[:, 1]), np.arctan2(d[:, 1], d[:, 0])))


def sensor_to_world_bearing(bearing_sensor: ArrayLike, heading: float) -> NDArray[np.float64]:
    """World bearing (clockwise from north) of a bearing measured clockwise from the bow."""
    return np.asarray(wrap_to_pi(np.asarray(bearing_sensor, dtype=float) + heading), dtype=float)
