"""Radar scans into a recording: plots as PointCloud2 on the radar topic (``/{sensor}/detections``).

Plots are written in the radar frame (REP-103: x forward, y left, z up; the mount on /tf_static
is a ``flu`` frame at the antenna), with ``range`` [m], ``bearing`` [rad] clockwise from the bow
(the layout's convention), ``time`` = seconds after the scan start at which the beam passed the
plot's azimuth, and ``intensity`` the plot's peak echo (0–255).
"""

from __future__ import annotations

import numpy as np

from seatwin.sensors.radar.config import RadarConfig
from seatwin.sensors.radar.model import RadarScan


def radar_mount(config: RadarConfig, ownship: str, sensor: str = "radar"):  # noqa: ANN201
    """The /tf_static mount of the radar frame on the ownship's body (FRD) frame."""
    from seatwin.recording import StaticTransform, mount_rotation
    from seatwin.recording.config import TopicConfig

    body = TopicConfig().body(ownship)
    return StaticTransform(body, sensor, (config.mount_x_m, config.mount_y_m, -config.antenna_height_m), mount_rotation("flu"))


def write_scan(writer, scan: RadarScan, config: RadarConfig, sensor: str = "radar") -> None:  # noqa: ANN001
    """Write one scan's plots on ``writer``'s radar topic for ``sensor`` in the radar frame."""
    topic = writer.topics.topic("radar", sensor=sensor)
    x = scan.range_m * np.cos(scan.azimuth)
    y = -scan.range_m * np.sin(scan.azimuth)
    writer.write_radar(
        topic, sensor, scan.time, x, y, np.zeros_like(x),
        intensity=scan.intensity, range=scan.range_m, bearing=scan.azimuth,
        time=scan.azimuth / (2 * np.pi) * config.rotation_period_s,
    )
