"""Point clouds for thesis Fig. 5.10: one recording's sweep nearest a time, in world north/east."""

from __future__ import annotations

import os
from dataclasses import dataclass, field

import numpy as np
from numpy.typing import NDArray

from seatwin.errors import InputError

POINTCLOUD2 = "sensor_msgs/msg/PointCloud2"


@dataclass
class CloudSnapshot:
    """A sweep in the world frame: points (N, 2) north/east, the ownship and the targets at its stamp."""

    time: float
    points: NDArray[np.float64]
    ownship: tuple[float, float]
    targets: list[tuple[str, float, float]] = field(default_factory=list)


def cloud_at(path: str | os.PathLike[str], t: float, sensor: str = "lidar") -> CloudSnapshot:
    """The ``sensor`` (lidar or radar) point cloud of a recording whose stamp is nearest ``t``, in world NED."""
    from seatwin.evaluation.truth import recording_truth
    from seatwin.perception.frames import recording_mounts, sensor_pose
    from seatwin.perception.from_recording import OwnshipTrajectory
    from seatwin.recording import open_bag

    with open_bag(path) as rec:
        truth = recording_truth(rec)
        own = [v for v in truth.values() if v.ownship]
        if not own:
            raise InputError(path, "no ownship ground truth: the sensor's position in the world is unknown")
        traj = OwnshipTrajectory.from_truth(own[0])
        radar = set(rec.radar_topics())
        topics = [tp for tp in rec.topics_of_type(POINTCLOUD2) if (tp in radar) == (sensor == "radar")]
        if not topics:
            raise InputError(path, f"no {sensor} point clouds in this recording")
        best = None
        for cloud in rec.point_clouds(topics):
            if best is None or abs(cloud.stamp - t) < abs(best.stamp - t):
                best = cloud
            elif cloud.stamp > t:
                break
        assert best is not None
        n, e, d, h = traj.pose_at(best.stamp)
        xyz = best.xyz()
        if best.frame_id == rec.topic_config.world_frame or best.frame_id.endswith("_ned"):
            world = xyz[:, :2]
        else:
            mounts = recording_mounts(rec.static_transforms())
            if best.frame_id not in mounts:
                raise InputError(path, f"no /tf_static mount for sensor frame {best.frame_id!r}; mounts: {sorted(mounts)}")
            world = sensor_pose(n, e, h, mounts[best.frame_id], d).to_world(xyz)[:, :2]
        targets = [
            (v.name, float(np.interp(best.stamp, v.time, v.north)), float(np.interp(best.stamp, v.time, v.east)))
            for v in truth.values()
            if not v.ownship and v.time[0] <= best.stamp <= v.time[-1]
        ]
    return CloudSnapshot(float(best.stamp), np.asarray(world, float), (n, e), targets)
