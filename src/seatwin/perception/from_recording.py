"""Scans from a recording: radar plots and lidar sweeps of a bag → :class:`Scan` in time order.

The sensor pose of every sweep is the ownship's ground-truth pose at the sweep's stamp
(interpolated linearly, heading unwrapped) composed with the sensor's mount from /tf_static.
Radar plots recorded in the world NED frame (imported datasets) are used as they are, seen
from the ownship position (the radar platform). Camera bearings come from a camera detector
(:mod:`seatwin.perception.camera_frames`: ``label`` on the recorded labels, ``onnx`` on the
images): the detections of all cameras at one instant form one bearing scan (a vessel seen by
two neighbouring cameras counts once).
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass, field
from typing import Any

import numpy as np
from numpy.typing import NDArray

from seatwin.errors import InputError, ParameterError
from seatwin.perception.camera_frames import CameraDetector, default_detector, detected_frames, missing_camera
from seatwin.perception.camera_frames import camera_topics as cam_topics
from seatwin.perception.frames import SensorPose, recording_mounts, sensor_pose
from seatwin.perception.lidar import LidarClustering, lidar_scan
from seatwin.perception.map_mask import NoMask, WaterMask
from seatwin.perception.measurements import Scan
from seatwin.perception.radar import RadarPlots, radar_scan

SENSORS = ("lidar", "radar", "camera")


@dataclass
class OwnshipTrajectory:
    """The ownship's pose over time, interpolated (positions linear, heading unwrapped)."""

    time: NDArray[np.float64]
    north: NDArray[np.float64]
    east: NDArray[np.float64]
    down: NDArray[np.float64]
    heading: NDArray[np.float64]
    name: str = "ownship"

    @classmethod
    def from_truth(cls, truth: Any) -> OwnshipTrajectory:
        order = np.argsort(truth.time, kind="stable")
        return cls(
            truth.time[order],
            truth.north[order],
            truth.east[order],
            truth.down[order],
            np.unwrap(truth.heading[order]),
            truth.name,
        )

    def pose_at(self, t: float) -> tuple[float, float, float, float]:
        """(north, east, down, heading) at ``t`` (held constant outside the recorded span)."""
        return tuple(float(np.interp(t, self.time, a)) for a in (self.north, self.east, self.down, self.heading))  # type: ignore[return-value]


@dataclass
class RecordingScans:
    """What :func:`scans_from_recording` found: the scans and how many sweeps there are in all."""

    scans: Iterator[Scan]
    total: int
    topics: dict[str, list[str]] = field(default_factory=dict)
    ownship: str | None = None


def _ownship(rec: Any, truth: dict[str, Any] | None) -> OwnshipTrajectory | None:
    """The ownship's trajectory from ``truth`` (vessel → truth), else from the bag's own ground-truth topics."""
    if truth is None:
        try:
            truth = rec.ground_truth()
        except InputError:
            return None
    own = [v for v in truth.values() if v.ownship]
    if not own:
        return None
    return OwnshipTrajectory.from_truth(own[0])


def _is_world_frame(frame_id: str, rec: Any) -> bool:
    return frame_id == rec.topic_config.world_frame or frame_id.endswith("_ned") or frame_id in ("world", "map")


def scans_from_recording(
    rec: Any,
    sensors: tuple[str, ...] = ("lidar", "radar"),
    *,
    mask: WaterMask | None = None,
    lidar: LidarClustering | None = None,
    radar: RadarPlots | None = None,
    truth: dict[str, Any] | None = None,
    camera: Any = None,
) -> RecordingScans:
    """Scans of the wanted ``sensors`` from an open :class:`seatwin.recording.Recording`.

    ``truth`` (vessel name → truth with ``ownship``, ``time``, ``north``…; e.g.
    :func:`seatwin.evaluation.truth.recording_truth`) poses the sensors; default: the bag's own topics.
    ``camera``: the camera detector, a :class:`~seatwin.sensors.camera.detector.LabelDetectorConfig`
    (default: its defaults, seeded with the recording's seed) or an
    :class:`~seatwin.sensors.camera.onnx_detector.OnnxDetectorConfig`.
    """
    for s in sensors:
        if s not in SENSORS:
            raise ParameterError("sensors", f"unknown sensor {s!r}; expected some of {', '.join(SENSORS)}")
    mask = mask or NoMask()
    radar_topics = rec.radar_topics() if "radar" in sensors else []
    lidar_topics = []
    if "lidar" in sensors:
        all_radar = set(rec.radar_topics())
        lidar_topics = [t for t in rec.topics_of_type("sensor_msgs/msg/PointCloud2") if t not in all_radar]
    detector = camera or default_detector(rec)
    camera_topics = cam_topics(rec, detector) if "camera" in sensors else []
    if "camera" in sensors and not camera_topics:
        raise missing_camera(rec, detector)
    found = {"radar": radar_topics, "lidar": lidar_topics, "camera": camera_topics}
    wanted = radar_topics + lidar_topics
    if not wanted and not camera_topics:
        raise InputError(rec.path, f"no {' or '.join(sensors)} topics in this recording; it has {sorted(rec.topics)}")
    n_camera = len(set(_stamps(rec, camera_topics))) if camera_topics else 0
    total = sum(rec.topics[t].count for t in wanted) + n_camera
    mounts = recording_mounts(rec.static_transforms())
    own = _ownship(rec, truth)

    def pose_for(frame_id: str, t: float) -> SensorPose:
        if own is None:
            raise InputError(
                rec.path,
                "the recording has no ownship ground truth (odometry/pose topics or a scenario "
                "beside it): the sensor pose in the world is unknown",
            )
        n, e, d, h = own.pose_at(t)
        mount = mounts.get(frame_id)
        if mount is None:
            raise InputError(rec.path, f"no /tf_static mount for sensor frame {frame_id!r}; mounts: {sorted(mounts)}")
        return sensor_pose(n, e, h, mount, d)

    def generate() -> Iterator[Scan]:
        import heapq

        streams = []
        if wanted:
            streams.append(cloud_scans())
        if camera_topics:
            streams.append(camera_scans(rec, camera_topics, detector, pose_for))
        yield from heapq.merge(*streams, key=lambda s: s.time)

    def cloud_scans() -> Iterator[Scan]:
        for cloud in rec.point_clouds(wanted):
            pts = cloud.points
            names = pts.dtype.names or ()
            if not {"x", "y", "z"} <= set(names) and not (cloud.topic in found["radar"] and {"x", "y"} <= set(names)):
                raise InputError(rec.path, f"PointCloud2 without x, y, z fields (it has {list(names)})", where=cloud.topic)
            if cloud.topic in found["radar"]:
                xy = np.column_stack((np.asarray(pts["x"], float), np.asarray(pts["y"], float)))
                if _is_world_frame(cloud.frame_id, rec):
                    if own is None:
                        raise InputError(
                            rec.path,
                            "world-frame radar plots need the radar platform's position: "
                            "the recording has no ownship ground truth",
                        )
                    n, e, _, _ = own.pose_at(cloud.stamp)
                    world = xy
                else:
                    pose = pose_for(cloud.frame_id, cloud.stamp)
                    z = np.asarray(pts["z"], float) if "z" in names else np.zeros(len(xy))
                    world = pose.to_world(np.column_stack((xy, z)))[:, :2]
                    n, e = pose.north, pose.east
                yield radar_scan(world, cloud.stamp, n, e, mask, radar, sensor="radar")
            else:
                pose = pose_for(cloud.frame_id, cloud.stamp)
                yield lidar_scan(cloud.xyz(), cloud.stamp, pose, mask, lidar, sensor="lidar")

    return RecordingScans(generate(), total, found, None if own is None else own.name)


def _stamps(rec: Any, topics: list[str]) -> list[int]:
    """Log times of the messages on ``topics`` (one camera instant may hold several cameras)."""
    return [ts for _, _, ts, _ in rec.raw_messages(set(topics))]


def camera_scans(rec: Any, topics: list[str], detector: CameraDetector, pose_for: Any) -> Iterator[Scan]:
    """Bearing scans of ``detector`` over ``topics``: one scan per instant, all cameras."""
    from seatwin.perception.measurements import MeasurementKind
    from seatwin.sensors.camera.detector import detection_bearings

    pending: list[tuple[float, float]] = []  # (bearing, confidence) at the current instant
    current: tuple[float, float, float] | None = None  # (time, north, east)

    def flush() -> Iterator[Scan]:
        if current is None:
            return
        kept: list[tuple[float, float]] = []
        for b, c in sorted(pending, key=lambda x: -x[1]):  # a vessel in two cameras' overlap counts once
            if all(abs((b - k + np.pi) % (2 * np.pi) - np.pi) > np.radians(1.5) for k, _ in kept):
                kept.append((b, c))
        z = np.array([b for b, _ in kept], float).reshape(-1, 1)
        yield Scan(current[0], "camera", MeasurementKind.BEARING, z, current[1], current[2], {"confidence": [c for _, c in kept]})

    for frame in detected_frames(rec, topics, detector):
        t = frame.time
        if current is not None and abs(t - current[0]) > 1e-6:
            yield from flush()
            pending = []
            current = None
        pose = pose_for(frame.frame_id, t)
        if current is None:
            current = (t, pose.north, pose.east)
        dets = frame.detections
        if dets:
            u = np.array([x.center_x for x in dets])
            v = np.array([x.center_y for x in dets])
            bearings = detection_bearings(u, v, frame.k, frame.d, pose.rotation)
            pending += [(float(b), x.confidence) for b, x in zip(bearings, dets, strict=True)]
    yield from flush()
