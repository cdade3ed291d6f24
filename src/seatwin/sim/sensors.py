"""What the loop steps: anything with a name, a rate, a phase and a ``record`` method.

A sensor's frame k happens at ``start + phase + k / rate``; ``record`` computes the frame and
writes its messages. Cameras and radar plug in as further :class:`SimSensor` classes.
"""

from __future__ import annotations

from dataclasses import asdict
from typing import Any, Protocol

from seatwin.recording import RecordingWriter, StaticTransform, TopicConfig, poses_from_scenario
from seatwin.recording.messages import quaternion_from_matrix
from seatwin.scenario import Scenario
from seatwin.sensors.lidar import Lidar
from seatwin.sensors.lidar_config import LidarMount


class SimSensor(Protocol):
    name: str
    rate_hz: float
    phase_s: float

    def static_transforms(self, topics: TopicConfig) -> list[StaticTransform]:
        """Mount transforms for /tf_static."""
        ...

    def parameters(self) -> dict[str, Any]:
        """What the manifest records about this sensor."""
        ...

    def record(self, writer: RecordingWriter, t: float, frame: int) -> None:
        """Compute frame ``frame`` at POSIX time ``t`` and write it."""
        ...


class GroundTruthSensor:
    """Ground truth of every vessel (PoseStamped, Odometry, NavSatFix of the ownship, /tf)."""

    def __init__(self, scenario: Scenario, rate_hz: float = 10.0, phase_s: float = 0.0, name: str = "ground_truth"):
        self.scenario, self.rate_hz, self.phase_s, self.name = scenario, float(rate_hz), float(phase_s), name

    def static_transforms(self, topics: TopicConfig) -> list[StaticTransform]:
        return []

    def parameters(self) -> dict[str, Any]:
        return {"kind": "ground_truth", "rate_hz": self.rate_hz, "phase_s": self.phase_s}

    def record(self, writer: RecordingWriter, t: float, frame: int) -> None:
        writer.write_ground_truth(t, poses_from_scenario(self.scenario, t))


class LidarSensor:
    """A spinning lidar on the ownship: one PointCloud2 per sweep, stamped at the sweep start.

    ``recorded_mount`` is the mount written to ``/tf_static`` and the manifest (default: the
    lidar's own); a different one simulates a miscalibrated extrinsic the consumer never sees.
    """

    def __init__(self, lidar: Lidar, phase_s: float = 0.0, name: str | None = None, carrier: str | None = None,
                 recorded_mount: LidarMount | None = None):
        self.lidar = lidar
        self.recorded_mount = recorded_mount if recorded_mount is not None else lidar.mount
        self.name = name or "lidar"
        self.rate_hz = float(lidar.config.rate_hz)
        self.phase_s = float(phase_s)
        self.carrier = carrier if carrier is not None else lidar.platform

    def static_transforms(self, topics: TopicConfig) -> list[StaticTransform]:
        if self.carrier is None:
            return []
        m = self.recorded_mount
        return [StaticTransform(topics.body(self.carrier), self.name, (float(m.x), float(m.y), float(m.z)),
                                quaternion_from_matrix(m.rotation()))]

    def parameters(self) -> dict[str, Any]:
        cfg = asdict(self.lidar.config)
        extra = {} if self.recorded_mount == self.lidar.mount else {"mount_simulated": asdict(self.lidar.mount)}
        return {
            "kind": "lidar",
            "rate_hz": self.rate_hz,
            "phase_s": self.phase_s,
            "range_model": self.lidar.range_model_name,
            "seed": self.lidar.seed,
            "carrier": self.carrier,
            "mount": asdict(self.recorded_mount),
            "config": cfg,
            **extra,
        }

    def record(self, writer: RecordingWriter, t: float, frame: int) -> None:
        s = self.lidar.sweep(t, frame)
        writer.write_sweep(writer.topics.topic("lidar", sensor=self.name), self.name, t,
                           s.x, s.y, s.z, s.intensity, s.ring, s.time)
