"""Lidar sweep → range-bearing measurements (thesis ch. 5.1.3: clusters of the point cloud).

1. Sensor-frame points → world NED through the sensor pose at the sweep time.
2. Drop the ownship's own returns: points inside its hull box (body frame, plus a margin).
3. Drop land/quay returns with a water mask (:mod:`.map_mask`), shrunk by ``land_margin`` from every
   land edge (returns from the vertical quay face at the water's edge), and points far above the
   water (bridges, buildings seen over the quay) or below it.
4. Cluster the rest in the horizontal plane (:mod:`.cluster`).
5. Each cluster's centroid becomes a measurement: range and bearing from the sensor in the
   world frame (:class:`~seatwin.perception.measurements.Scan` of kind ``range_bearing``).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from seatwin.perception.cluster import cluster_moments, minor_spread
from seatwin.perception.frames import SensorPose
from seatwin.perception.map_mask import NoMask, WaterMask
from seatwin.perception.measurements import MeasurementKind, Scan, cartesian_to_polar


@dataclass(frozen=True)
class LidarClustering:
    """Parameters of the lidar pipeline (defaults for a VLP-16 on milliAmpere in a harbour)."""

    ownship_half_length: float = 2.5
    """Half the ownship hull length [m] (milliAmpere is 5 m × 2.8 m)."""
    ownship_half_beam: float = 1.4
    ownship_margin: float = 1.0
    """Extra metres around the hull box (antenna masts, people on deck)."""
    max_height: float = 8.0
    """Points higher than this above the water [m] are dropped (no boat in a harbour is taller)."""
    min_height: float = -1.0
    """Points lower than this [m] (below the water surface) are dropped as noise."""
    eps: float = 1.5
    """Clustering distance [m]: above the VLP-16 ring spacing on a boat hull within ~40 m."""
    min_points: int = 3
    max_range: float = 100.0
    """VLP-16 range [m]."""
    land_margin: float = 1.5
    """Points within this distance [m] of land in the water mask are dropped as quay returns. Our choice:
    a quay face lies on the mask's land edge, blurred by the 1 m raster cells and its alignment; 1.5 m
    removes it. The tradeoff: the inner 1.5 m of a boat moored against the quay is dropped too — a beamier
    boat keeps its outer side (its cluster, and track, sits a little off the quay); a dinghy under 1.5 m
    beam alongside the quay is lost."""


def lidar_scan(
    points: NDArray[np.float64],
    time: float,
    pose: SensorPose,
    mask: WaterMask | None = None,
    params: LidarClustering | None = None,
    sensor: str = "lidar",
) -> Scan:
    """Cluster one sweep (``points`` (N, 3) in the sensor frame) into a range-bearing :class:`Scan`."""
    p = params or LidarClustering()
    mask = mask or NoMask()
    pts = np.asarray(points, dtype=float).reshape(-1, 3)
    pts = pts[np.isfinite(pts).all(axis=1)]
    world = pose.to_world(pts)
    body = pose.to_body(world)
    own = (np.abs(body[:, 0]) <= p.ownship_half_length + p.ownship_margin) & (
        np.abs(body[:, 1]) <= p.ownship_half_beam + p.ownship_margin
    )
    height = -world[:, 2]
    keep = ~own & (height <= p.max_height) & (height >= p.min_height)
    rng = np.hypot(world[:, 0] - pose.north, world[:, 1] - pose.east)
    keep &= rng <= p.max_range
    keep[keep] = mask.clear_of_land(world[keep, 0], world[keep, 1], p.land_margin)
    centroids, counts, cov = cluster_moments(world[keep, :2], p.eps, p.min_points)
    z = cartesian_to_polar(centroids, (pose.north, pose.east))
    return Scan(
        time,
        sensor,
        MeasurementKind.RANGE_BEARING,
        z,
        pose.north,
        pose.east,
        extra={
            "cluster_sizes": counts,
            "cluster_thickness": minor_spread(cov),
            "cluster_cov": cov,
            "n_points": int(pts.shape[0]),
            "n_kept": int(keep.sum()),
        },
    )


SHAPE_FLOOR_M = 0.01
"""Added to a cluster's thickness before its logarithm (a noiseless planar cluster has thickness ~0)."""


def cluster_shape_features(scan: Scan) -> NDArray[np.float64]:
    """(M, 2) shape features of a lidar scan's clusters: log point count, log(thickness + 1 cm) — what
    range noise (thickness), ray drop and range dissipation (points) change; (0, 2) for other scans."""
    sizes, thick = scan.extra.get("cluster_sizes"), scan.extra.get("cluster_thickness")
    if sizes is None or thick is None:
        return np.zeros((0, 2))
    return np.column_stack([np.log(np.asarray(sizes, float)), np.log(np.asarray(thick, float) + SHAPE_FLOOR_M)])


def cluster_moment_rows(scan: Scan) -> NDArray[np.float64] | None:
    """(M, 4) per cluster of a lidar scan: point count and horizontal covariance ``nn, ne, ee`` [m²] (population,
    about the centroid) — what the sensor-level lidar terms (:mod:`seatwin.evaluation.lidar_terms`) need; None
    for a scan that is not a clustered lidar sweep (radar plots)."""
    sizes, cov = scan.extra.get("cluster_sizes"), scan.extra.get("cluster_cov")
    if sizes is None or cov is None:
        return None
    c = np.asarray(cov, float).reshape(-1, 2, 2)
    return np.column_stack([np.asarray(sizes, float), c[:, 0, 0], c[:, 0, 1], c[:, 1, 1]])
