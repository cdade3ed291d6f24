"""Sensor frames as Gemini puts them on the wire (``CameraStreamingRequest.data``, ``LidarStreamingRequest.data``,
``SensordataResponse.data``), and back."""

from __future__ import annotations

from typing import Any

import numpy as np

from seatwin.recording.pointcloud import VLP16_LAYOUT, pack


def lidar_bytes(sweep: Any) -> bytes:
    """One sweep's points (columns x, y, z, intensity, ring, time) in the Table 4.2 layout, little endian."""
    data = pack(VLP16_LAYOUT, x=sweep.x, y=sweep.y, z=sweep.z, intensity=sweep.intensity, ring=sweep.ring, time=sweep.time)
    return np.ascontiguousarray(data).tobytes()


def camera_bytes(bgr: np.ndarray) -> bytes:
    """An H×W×3 bgr8 image (rows top down) as Gemini puts a camera image on the wire: R, G, B bytes a pixel,
    rows bottom to top (Unity's RGB24 GPU readback; Gemini's ROS adapter flips the rows and converts
    RGB to BGR before publishing bgr8)."""
    return np.ascontiguousarray(np.asarray(bgr, np.uint8)[::-1, :, ::-1]).tobytes()


def image_from_wire(data: bytes, width: int, height: int) -> np.ndarray:
    """:func:`camera_bytes` undone: the H×W×3 bgr8 image, rows top down (what Gemini's ROS adapter publishes)."""
    return np.ascontiguousarray(np.frombuffer(data, np.uint8).reshape(height, width, 3)[::-1, :, ::-1])
