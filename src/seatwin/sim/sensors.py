"""What the loop steps: a sensor names its frame times, captures a frame, and records it.

``capture(t, frame)`` computes a frame at its own time (pure: no file is written);
``record(writer, t, data)`` writes the captured frame's messages. Periodic sensors take their
times from :func:`seatwin.sim.loop.periodic_times` (frame k at ``start + phase + k / rate``).
Lidar, ground truth and radar (:mod:`seatwin.sim.radar`) plug in here; cameras come as further classes.
"""

from __future__ import annotations

import math
from typing import Any, Protocol

import numpy as np
from numpy.typing import NDArray

from seatwin.recording import RecordingWriter, StaticTransform, TopicConfig, VesselPose
from seatwin.recording.tf_tree import sensor_mount
from seatwin.scenario import Scenario
from seatwin.sensors.lidar import Lidar
from seatwin.sensors.lidar_config import LidarMount
from seatwin.sim.poses import PoseTable, poses_from_scenario
from seatwin.sim.timing import periodic_times, periodic_times_from


class SimSensor(Protocol):
    name: str

    def frame_times(self, t0: float, t1: float) -> NDArray[np.float64]:
        """POSIX times of this sensor's frames in [t0, t1), ascending; frame k is the k-th."""
        ...

    def static_transforms(self, topics: TopicConfig) -> list[StaticTransform]:
        """Mount transforms for /tf_static."""
        ...

    def parameters(self) -> dict[str, Any]:
        """What the manifest records about this sensor."""
        ...

    def capture(self, t: float, frame: int) -> Any:
        """Compute frame ``frame`` at POSIX time ``t``."""
        ...

    def record(self, writer: RecordingWriter, t: float, data: Any) -> None:
        """Write a frame ``capture`` returned."""
        ...


class Periodic:
    """Frame times of a sensor with ``rate_hz`` and ``phase_s``."""

    rate_hz: float
    phase_s: float

    def frame_times(self, t0: float, t1: float) -> NDArray[np.float64]:
        return periodic_times(t0, t1, self.rate_hz, self.phase_s)

    def frame_times_from(self, t0: float, t1: float, first: int) -> NDArray[np.float64]:
        """``frame_times(t0, t1)[first:]`` at a cost independent of ``first`` (the stepper's later increments)."""
        return periodic_times_from(t0, t1, self.rate_hz, self.phase_s, first)


class GroundTruthSensor(Periodic):
    """Ground truth of every vessel (PoseStamped, Odometry, NavSatFix of the ownship, /tf).

    :meth:`frame_times` also computes every frame's poses at once (:class:`~seatwin.sim.poses.PoseTable`:
    vectorised, the ownship's WGS-84 position included); a frame outside that table is computed alone.
    """

    def __init__(self, scenario: Scenario, rate_hz: float = 10.0, phase_s: float = 0.0, name: str = "ground_truth"):
        self.scenario, self.rate_hz, self.phase_s, self.name = scenario, float(rate_hz), float(phase_s), name
        self._table: PoseTable | None = None
        self._markers: tuple[RecordingWriter, bytes, float] | None = None
        """(the writer, the run's MarkerArray bytes, when they were last written)."""

    def frame_times(self, t0: float, t1: float) -> NDArray[np.float64]:
        times = super().frame_times(t0, t1)
        self._table = PoseTable.from_scenario(self.scenario, times)
        return times

    def static_transforms(self, topics: TopicConfig) -> list[StaticTransform]:
        return []

    def parameters(self) -> dict[str, Any]:
        return {"kind": "ground_truth", "rate_hz": self.rate_hz, "phase_s": self.phase_s}

    def capture(self, t: float, frame: int) -> list[VesselPose]:
        table = self._table
        if table is not None and 0 <= frame < len(table.times) and table.times[frame] == t:
            return table.poses(frame)
        return poses_from_scenario(self.scenario, t)

    def record(self, writer: RecordingWriter, t: float, data: list[VesselPose]) -> None:
        from seatwin.recording.foxglove import MARKER_PERIOD_S

        writer.write_ground_truth(t, data)
        if self._markers is None or self._markers[0] is not writer:
            self._markers = (writer, self._marker_bytes(writer, data), -math.inf)
        w, data_bytes, last = self._markers
        if t - last >= MARKER_PERIOD_S - 1e-6:
            writer.write_raw(writer.topics.markers, "visualization_msgs/msg/MarkerArray", t, data_bytes)
            self._markers = (w, data_bytes, t)

    def _marker_bytes(self, writer: RecordingWriter, data: list[VesselPose]) -> bytes:
        """The vessels' markers, serialised once a run: they sit in the body frames (frame-locked, stamp 0 =
        the latest /tf), so the message never changes."""
        from seatwin.recording.foxglove import marker_array_bytes, vessel_marker_specs

        dims = {v.name: v.dimensions for v in self.scenario.vessels}
        vessels = []
        for p in data:
            d = dims.get(p.name)
            size = (d.length, d.beam, d.height) if d is not None else (0.0, 0.0, 0.0)  # unknown size: the name only
            vessels.append((p.name, writer.topics.body(p.name), size, p.ownship))
        return marker_array_bytes(vessel_marker_specs(vessels), ros1=writer.format == "ros1")


class LidarSensor(Periodic):
    """A spinning lidar on the ownship: one PointCloud2 per sweep, stamped at the sweep start.

    ``recorded_mount`` is the mount written to ``/tf_static`` and the manifest (default: the
    lidar's own); a different one simulates a miscalibrated extrinsic the consumer never sees.
    """

    def __init__(
        self,
        lidar: Lidar,
        phase_s: float = 0.0,
        name: str | None = None,
        carrier: str | None = None,
        recorded_mount: LidarMount | None = None,
    ):
        self.lidar = lidar
        self.recorded_mount = recorded_mount if recorded_mount is not None else lidar.mount
        self.name = name or "lidar"
        self.rate_hz = float(lidar.config.rate_hz)
        self.phase_s = float(phase_s)
        self.carrier = carrier if carrier is not None else lidar.platform

    def static_transforms(self, topics: TopicConfig) -> list[StaticTransform]:
        """The mount on the carrier's ``base_link``; the roll (the thesis's 180°: upside down) as its own
        transform below ``{carrier}/lidar_upright`` (:func:`~seatwin.recording.tf_tree.sensor_mount`)."""
        if self.carrier is None:
            return []
        m = self.recorded_mount
        return sensor_mount(
            topics, self.carrier, topics.sensor(self.carrier, self.name), m.translation, m.rotation(), math.radians(m.roll_deg)
        )

    def parameters(self) -> dict[str, Any]:
        cfg = self.lidar.config.model_dump()
        extra = {} if self.recorded_mount == self.lidar.mount else {"mount_simulated": self.lidar.mount.model_dump()}
        return {
            "kind": "lidar",
            "rate_hz": self.rate_hz,
            "phase_s": self.phase_s,
            "range_model": self.lidar.range_model_name,
            "seed": self.lidar.seed,
            "carrier": self.carrier,
            "mount": self.recorded_mount.model_dump(),
            "config": cfg,
            **extra,
        }

    def capture(self, t: float, frame: int) -> Any:
        return self.lidar.sweep(t, frame)

    def record(self, writer: RecordingWriter, t: float, data: Any) -> None:
        s = data
        tp = writer.topics
        frame = tp.sensor(self.carrier, self.name)
        writer.write_sweep(tp.topic("lidar", sensor=self.name), frame, t, s.x, s.y, s.z, s.intensity, s.ring, s.time)
