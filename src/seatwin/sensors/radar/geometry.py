"""What the radar illuminates: a fan of rays per spoke cast through the engine.

Per spoke the fan holds rays aimed at a point 0.5 m above the water at a geometric series of
ranges (ratio 1.4, so a hull 0–2 m high is crossed by at least one ray at every range for
antenna heights of a few metres) plus a few rays at and above the horizon for tall
structures, all within the vertical beam. The first hit of each ray is a reflector; a ray's
hit below the water line is dropped (the water stops it). Hits are grouped per object: its
cells (spoke, range sample), its visible cross-range width and height, and its range.
Occlusion is the engine's: a ray stops at the nearest object.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from seatwin.sensors.radar.config import RadarConfig

AIM_HEIGHT_M = 0.5
RANGE_RATIO = 1.4
UP_ANGLES_DEG = (0.0, 1.0, 3.0, 6.0)
"""Elevations above the horizon [deg] (kept if within half the vertical beam)."""


@dataclass(frozen=True)
class AntennaPose:
    """The antenna in the world (local NED): position [m] and the platform heading [rad, clockwise from north]."""

    north: float
    east: float
    heading: float
    height: float


def depression_angles(cfg: RadarConfig) -> NDArray[np.float64]:
    """Angles below the horizon [rad] of the fan's rays (negative = above the horizon)."""
    h = cfg.antenna_height_m
    half = 0.5 * cfg.vertical_beam_width
    angles: list[float] = []
    if h > AIM_HEIGHT_M:
        r = max(cfg.min_range_m, 1.0)
        while r < cfg.max_range_m * RANGE_RATIO:
            angles.append(float(np.arctan2(h - AIM_HEIGHT_M, r)))
            r *= RANGE_RATIO
    angles += [-np.radians(u) for u in UP_ANGLES_DEG]
    a = np.unique(np.round(np.asarray(angles), 9))
    return a[np.abs(a) <= half]


def fan_directions(cfg: RadarConfig, heading: float) -> tuple[NDArray[np.float32], NDArray[np.int64]]:
    """Unit ray directions (world NED) of one rotation and the spoke index of each ray."""
    dep = depression_angles(cfg)
    spokes = np.arange(cfg.n_spokes)
    az = heading + (spokes + 0.5) * cfg.spoke_step
    ca, sa = np.cos(az)[:, None], np.sin(az)[:, None]
    cd, sd = np.cos(dep)[None, :], np.sin(dep)[None, :]
    d = np.stack(np.broadcast_arrays(ca * cd, sa * cd, np.ones_like(ca) * sd), axis=-1).reshape(-1, 3)
    return d.astype(np.float32), np.repeat(spokes, len(dep))


@dataclass
class ObjectReturns:
    """What one object returns in one scan (before detection): its cells and visible size."""

    object_id: int
    spoke: NDArray[np.int64]
    sample: NDArray[np.int64]
    range_m: float
    """Median slant range of its hits."""
    width_m: float
    """Visible cross-range width: distinct spokes hit × spoke step × range."""
    height_m: float
    """Highest hit above the water line."""

    @property
    def area_m2(self) -> float:
        return self.width_m * max(self.height_m, 0.1)


def illuminate(cfg: RadarConfig, pose: AntennaPose, caster: object, exclude: frozenset[int] = frozenset()) -> list[ObjectReturns]:
    """Cast the fan from the antenna through ``caster`` (an engine ``RayCaster``); returns per object.

    ``exclude`` lists object ids the antenna ignores (the ownship's own hull).
    """
    d, spoke = fan_directions(cfg, pose.heading)
    origin = np.array([pose.north, pose.east, -pose.height], np.float32)
    o = np.broadcast_to(origin, d.shape)
    hits = caster.cast(o, d, max_range=cfg.max_range_m)  # type: ignore[attr-defined]
    rng = np.asarray(hits.range, float)
    oid = np.asarray(hits.object_id, np.int64)
    z = origin[2] + np.where(np.isfinite(rng), rng, 0.0) * d[:, 2]
    keep = (oid >= 0) & (rng >= cfg.min_range_m) & (rng <= cfg.max_range_m) & (z <= 0.05)
    if exclude:
        keep &= ~np.isin(oid, list(exclude))
    rng, oid, spoke, height = rng[keep], oid[keep], spoke[keep], -z[keep]
    sample = np.floor((rng - cfg.range_start_m) / cfg.range_increment_m).astype(np.int64)
    out = []
    for obj in np.unique(oid):
        m = oid == obj
        r_med = float(np.median(rng[m]))
        n_sp = len(np.unique(spoke[m]))
        out.append(ObjectReturns(int(obj), spoke[m], sample[m], r_med, n_sp * cfg.spoke_step * r_med, float(height[m].max())))
    return out
