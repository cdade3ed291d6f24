"""The marine radar as a :class:`seatwin.sim.sensors.SimSensor`: one rotation a frame, plots on the radar topic.

Plots are written in the radar frame (REP-103: x forward, y left, z up; the mount on /tf_static
is a ``flu`` frame at the antenna), with ``range`` [m], ``bearing`` [rad] clockwise from the bow
(the layout's convention), ``time`` = seconds after the scan start at which the beam passed the
plot's azimuth, and ``intensity`` the plot's peak echo (0–255).
"""

from __future__ import annotations

from collections.abc import Sequence
from typing import Any

import numpy as np
from numpy.typing import NDArray

from seatwin.errors import ParameterError
from seatwin.geo import mount_matrix
from seatwin.recording import RecordingWriter, StaticTransform, TopicConfig
from seatwin.recording.tf_tree import sensor_mount
from seatwin.sensors.radar.config import RadarConfig
from seatwin.sensors.radar.model import RadarModel, RadarScan
from seatwin.sim.timing import TIME_EPS_S, periodic_times, periodic_times_from


def radar_mount(
    config: RadarConfig, ownship: str, sensor: str, topics: TopicConfig, frame_id: str | None = None
) -> list[StaticTransform]:
    """The /tf_static mount of the radar frame (``{ownship}/{sensor}``, or ``frame_id`` where the data names its own,
    FLU at the antenna) on the ownship's ``base_link``."""
    translation = (config.mount_x_m, config.mount_y_m, -config.antenna_height_m)
    frame = frame_id if frame_id is not None else topics.sensor(ownship, sensor)
    return sensor_mount(topics, ownship, frame, translation, mount_matrix("flu"))


def write_scan(
    writer: RecordingWriter, scan: RadarScan, config: RadarConfig, sensor: str = "radar", carrier: str | None = None
) -> None:
    """Write one scan's plots on ``writer``'s radar topic for ``sensor`` in the radar frame (of ``carrier``)."""
    x = scan.range_m * np.cos(scan.azimuth)
    y = -scan.range_m * np.sin(scan.azimuth)
    writer.write_radar(
        writer.topics.topic("radar", sensor=sensor),
        writer.topics.sensor(carrier, sensor),
        scan.time,
        x,
        y,
        np.zeros_like(x),
        intensity=scan.intensity,
        range=scan.range_m,
        bearing=scan.azimuth,
        time=scan.azimuth / (2 * np.pi) * config.rotation_period_s,
    )


class RadarSensor:
    """``model`` on vessel ``ownship`` of ``scene``: a scan per rotation, or at the given ``times``.

    ``times`` (POSIX, ascending) replays a real recording's scan instants (the fidelity replica);
    ``frame_ids`` (with strictly increasing ``times``) numbers those frames for the random draws
    (default: a frame's position in the loop's window), so a subset of a recording's scans draws
    as it would in the whole; ``with_spokes`` also keeps each rotation's raw spokes on the
    captured :class:`RadarScan`.
    """

    def __init__(
        self,
        model: RadarModel,
        scene: Any,
        ownship: str,
        *,
        times: Sequence[float] | None = None,
        frame_ids: Sequence[int] | None = None,
        phase_s: float = 0.0,
        with_spokes: bool | None = None,
        name: str = "radar",
    ):
        self.model, self.scene, self.ownship, self.name = model, scene, ownship, name
        self.times = None if times is None else np.asarray(times, dtype=np.float64)
        self.frame_ids = None if frame_ids is None else np.asarray(frame_ids, dtype=np.int64)
        if self.frame_ids is not None and (
            self.times is None or self.frame_ids.shape != self.times.shape or (np.diff(self.times) <= 0).any()
        ):
            raise ParameterError("frame_ids", "expected one frame id per time, with strictly increasing times")
        self.rate_hz = 1.0 / float(model.config.rotation_period_s)
        self.phase_s = float(phase_s)
        self.with_spokes = with_spokes

    def frame_times(self, t0: float, t1: float) -> NDArray[np.float64]:
        if self.times is None:
            return periodic_times(t0, t1, self.rate_hz, self.phase_s)
        rel = self.times - float(t0)
        return self.times[(rel >= -TIME_EPS_S) & (rel < float(t1) - float(t0) - TIME_EPS_S)]

    def frame_times_from(self, t0: float, t1: float, first: int) -> NDArray[np.float64]:
        """``frame_times(t0, t1)[first:]``; periodic rotations at a cost independent of ``first``."""
        if self.times is None:
            return periodic_times_from(t0, t1, self.rate_hz, self.phase_s, first)
        return self.frame_times(t0, t1)[first:]

    def static_transforms(self, topics: TopicConfig) -> list[StaticTransform]:
        return radar_mount(self.model.config, self.ownship, self.name, topics)

    def parameters(self) -> dict[str, Any]:
        return {
            "kind": "radar",
            "rate_hz": self.rate_hz,
            "phase_s": self.phase_s,
            "seed": self.model.seed,
            "carrier": self.ownship,
            "config": self.model.config.model_dump(mode="json", exclude={"fit"}),
        }

    def capture(self, t: float, frame: int) -> RadarScan:
        from seatwin.sensors.radar.world import scan_scene

        if self.frame_ids is not None:
            frame = int(self.frame_ids[np.searchsorted(self.times, t)])
        return scan_scene(self.model, self.scene, self.ownship, frame, t, with_spokes=self.with_spokes)

    def record(self, writer: RecordingWriter, t: float, data: RadarScan) -> None:
        write_scan(writer, data, self.model.config, sensor=self.name, carrier=self.ownship)
