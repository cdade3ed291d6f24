"""Camera bearing measurements (thesis 5.1.3: the bearing model of the camera).

A detection at horizontal pixel ``u`` of a pinhole camera with focal length ``fx`` and
principal point ``cx`` lies at the angle ``atan((u − cx) / fx)`` to the right of the optical
axis; adding the optical axis' world bearing gives the world bearing the tracker's
:class:`~seatwin.tracking.models.BearingModel` expects. The detector itself comes with the
camera work; this module turns its boxes' centres into a :class:`Scan`.
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike

from seatwin.geo import wrap_to_pi
from seatwin.perception.measurements import MeasurementKind, Scan


def pixel_bearing(u: ArrayLike, fx: float, cx: float) -> np.ndarray:
    """Angle [rad] right of the optical axis of horizontal pixel coordinates ``u``."""
    return np.arctan2(np.asarray(u, dtype=float) - cx, fx)


def camera_scan(
    u: ArrayLike,
    time: float,
    fx: float,
    cx: float,
    axis_bearing: float,
    sensor_north: float,
    sensor_east: float,
    sensor: str = "camera",
) -> Scan:
    """Bearings of detections at pixel columns ``u`` for a camera whose optical axis points at ``axis_bearing``."""
    b = np.asarray(wrap_to_pi(pixel_bearing(u, fx, cx) + axis_bearing), dtype=float).reshape(-1, 1)
    return Scan(time, sensor, MeasurementKind.BEARING, b, sensor_north, sensor_east)
