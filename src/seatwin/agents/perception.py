"""An agent's perception in process: seatwin's own lidar clustering and radar plots feeding its JIPDA tracker.

Sensor frames as :class:`~seatwin.agents.interface.SensorFrame` → :func:`seatwin.perception.lidar.lidar_scan` /
:func:`seatwin.perception.radar.radar_scan` (land masked with the harbour's water mask) → one
:class:`seatwin.tracking.JIPDATracker` → confirmed tracks. A ``truth`` frame passes the true targets through instead
(perfect perception).
"""

from __future__ import annotations

import math
from collections.abc import Sequence

import numpy as np

from seatwin.agents.interface import SensorFrame, TrackEstimate, TruthTarget
from seatwin.perception.frames import sensor_pose
from seatwin.perception.lidar import LidarClustering, lidar_scan
from seatwin.perception.map_mask import WaterMask, load_mask
from seatwin.perception.measurements import Scan
from seatwin.perception.radar import RadarPlots, radar_scan
from seatwin.tracking.config import load_tuning
from seatwin.tracking.tracker import JIPDATracker


class TrackingPerception:
    """Lidar/radar frames → JIPDA tracks (tuning ``tuning``: a preset name or file), one tracker per sensor.

    One tracker per sensor, because the tracker's missed-detection update knows no sensor coverage: a lidar sweep
    (100 m) would count every radar track beyond its range as missed 10 times a second and kill it; and a radar
    rotation, complete only 2.5 s after its stamp, would arrive out of order among the lidar sweeps. The tracks are
    the lidar tracker's, plus the radar tracker's farther than :data:`MERGE_M` from all of them.
    """

    MERGE_M = 10.0

    def __init__(self, harbour: str, tuning: str = "synthetic"):
        self.mask: WaterMask = load_mask(harbour)
        self.config = load_tuning(tuning)
        self.trackers: dict[str, JIPDATracker] = {}
        self.lidar = LidarClustering()
        self.radar = RadarPlots()

    def scan(self, frame: SensorFrame) -> Scan | None:
        """A frame's measurements (None for frames this perception does not read)."""
        nav = frame.navigation
        if frame.sensor == "lidar":
            s = frame.data
            pts = np.column_stack((s.x, s.y, s.z)).astype(np.float64)
            pose = sensor_pose(nav.north, nav.east, nav.heading, frame.mount)
            return lidar_scan(pts, frame.time, pose, self.mask, self.lidar)
        if frame.sensor == "radar":
            r = frame.data
            return radar_scan(r.positions, frame.time, r.antenna.north, r.antenna.east, self.mask, self.radar)
        return None

    def update(self, frames: Sequence[SensorFrame]) -> None:
        for f in frames:
            scan = self.scan(f)
            if scan is not None:
                if f.sensor not in self.trackers:
                    self.trackers[f.sensor] = JIPDATracker(self.config, self.mask)
                self.trackers[f.sensor].step(scan)

    def tracks(self) -> list[TrackEstimate]:
        out: list[TrackEstimate] = []
        for sensor in sorted(self.trackers, key=lambda s: s != "lidar"):  # lidar first
            t = self.trackers[sensor]
            offset = 0 if sensor == "lidar" else 1_000_000
            for i in np.flatnonzero(t.confirmed):
                n, e = float(t.x[i, 0]), float(t.x[i, 2])
                if any(math.hypot(o.north - n, o.east - e) < self.MERGE_M for o in out):
                    continue
                out.append(TrackEstimate(offset + int(t.ids[i]), n, e, float(t.x[i, 1]), float(t.x[i, 3])))
        return out


class PerfectPerception:
    """Ground truth as tracks: every target, exactly, from the latest ``truth`` frame."""

    def __init__(self) -> None:
        self._latest: tuple[TruthTarget, ...] = ()
        self._ids: dict[str, int] = {}

    def update(self, frames: Sequence[SensorFrame]) -> None:
        for f in frames:
            if f.sensor == "truth":
                self._latest = tuple(f.data)

    def tracks(self) -> list[TrackEstimate]:
        out = []
        for t in self._latest:
            i = self._ids.setdefault(t.name, len(self._ids) + 1)
            out.append(TrackEstimate(i, t.north, t.east, t.v_north, t.v_east))
        return out
