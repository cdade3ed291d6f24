"""The depth-buffer lidar range model: each beam's point as the thesis's GPU method gives it.

How it is computed — rays through exactly the pixel centres the filter selects, not a
rasteriser — and why that reproduces the depth buffer's error:

1. A rasteriser fills pixel ``(x^d, y^d)`` with the depth of the nearest surface *at the
   pixel centre*: it samples coverage at pixel centres and interpolates ``z^i`` (affine in
   screen space for a planar triangle, since ``z^i`` is affine in ``1/z^v``) at that
   centre; the depth test keeps the nearest triangle. That is exactly the first hit of the
   ray from the camera centre through the pixel centre, clipped to ``[n, f]`` in depth.
   The ray is cast from the near plane (near-plane clipping) and hits beyond the far
   plane are misses (the cleared buffer).
2. The depth is stored as the integer ``z^d`` of 4.8/4.9 with ``N_c,d`` levels: the same
   truncation is applied here, in float64 (the GPU's float32 interpolation error,
   ~2^-24 relative in NDC, is of the order of one ``z^d`` step and not modelled).
3. The point cloud is back-projected from ``(x^d + ½, y^d + ½, z^d)`` by 4.37–4.40 and
   rotated into the first camera's frame by 4.41–4.42, then into the sensor frame.

So every point carries both errors the thesis analyses: the pixel (the sampled ray is
the pixel centre's, not the beam's; ``x^v_ε``, ``y^v_ε``) and the depth step (``z^v_ε``).
Without the filter (``use_filter=False``) the pixel comes from the legacy regular grid
(:func:`~seatwin.sensors.depthbuffer.filter.legacy_grid`), which adds the beam shape
error. Only geometry inside one pixel is lost: sub-pixel triangles the rasteriser would
miss or catch by coverage rules appear here exactly as the centre ray sees them.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike, NDArray

from seatwin.sensors.depthbuffer.filter import AzimuthGrid, PixelMap, legacy_grid, sensor_angles, spherical_filter
from seatwin.sensors.depthbuffer.projection import (
    DEPTH_24BIT,
    VIEW_TO_SENSOR,
    DepthCamera,
    back_project,
    camera_hfov,
    camera_vfov,
    camera_width,
    depth_to_discrete,
    pixel_ray,
    rotation_y,
)

Cut = Callable[[NDArray[np.float64], NDArray[np.float64]], NDArray[np.float64]]
"""``cut(origins, unit_directions) -> max_range`` per ray (e.g. where the ray meets the water)."""


@dataclass(frozen=True)
class DepthBufferConfig:
    """Depth-buffer parameters of a lidar (defaults: Table 4.1's lidar, consistent row ``lidar_eq417``)."""

    n_c: int = 8
    n_ch: int = 3104
    n_cd: int = DEPTH_24BIT
    near: float = 0.05
    far: float = 100.0
    vfov_s: float = math.radians(30.0)
    """The sensor's vertical field of view; VFOV_c follows by 4.17, N_c,w by 4.16."""
    use_filter: bool = True
    """True: the spherical projection filter; False: the legacy Gemini regular grid."""

    def camera(self) -> DepthCamera:
        """The virtual camera (4.14, 4.16 rounded to the nearest pixel, 4.17)."""
        hfov = camera_hfov(self.n_c)
        n_cw = max(1, round(camera_width(self.n_ch, self.vfov_s, hfov)))
        return DepthCamera(n_cw, self.n_ch, camera_vfov(self.vfov_s, hfov), self.near, self.far, self.n_cd)


@dataclass(frozen=True)
class DepthBufferHits:
    """Per beam: the back-projected point (sensor frame, NaN = no return), its range and the hit."""

    points: NDArray[np.float64]
    range: NDArray[np.float64]
    """``|point|`` [m]; ``inf`` where the buffer holds nothing (no surface within ``[n, f]``)."""
    object_id: NDArray[np.int32]
    normal: NDArray[np.float32]
    """Unit normal of the surface in the pixel (world frame), 0 on a miss."""
    z_d: NDArray[np.int64]
    """The stored depth ``z^d`` (``N_c,d`` − 1 where nothing was hit)."""

    @property
    def hit(self) -> NDArray[np.bool_]:
        return self.object_id >= 0


class DepthBufferLidar:
    """Depth-buffer sampling for fixed beam directions; the filter is precomputed once.

    ``directions``: (N, 3) unit beam directions in the sensor frame (x forward, y left, z up);
    ``grid``: their integer azimuth indices when they lie on a regular grid (a lidar's columns),
    which then assign the beams to cameras exactly (see :mod:`.filter`).
    """

    def __init__(self, directions: ArrayLike, config: DepthBufferConfig = DepthBufferConfig(), grid: AzimuthGrid | None = None):
        self.config = config
        self.camera = config.camera()
        d = np.atleast_2d(np.asarray(directions, dtype=np.float64))
        self.directions = d / np.linalg.norm(d, axis=1, keepdims=True)
        if grid is not None and not grid.matches(sensor_angles(self.directions)[0]):
            raise ValueError("the beam directions do not lie on the given azimuth grid")
        self.grid = grid
        make = spherical_filter if config.use_filter else legacy_grid
        self.pixels: PixelMap = make(self.directions, self.camera, config.n_c, grid)
        ray_v = pixel_ray(self.pixels.x_d, self.pixels.y_d, self.camera)  # z = −1 per unit depth
        self.depth_scale = np.linalg.norm(ray_v, axis=1)
        """Range per unit depth along each sampled pixel ray."""
        self._rot = VIEW_TO_SENSOR @ rotation_y(self.pixels.camera, config.n_c)  # (N, 3, 3)
        self.sample_directions = np.einsum("nij,nj->ni", self._rot, ray_v / self.depth_scale[:, None])
        """Unit sensor-frame directions of the pixel-centre rays that are actually sampled."""
        cos = np.clip(np.einsum("ij,ij->i", self.directions, self.sample_directions), -1.0, 1.0)
        self.deviation = np.arccos(cos)
        """Angle between each beam and its sampled ray [rad]."""

    def __len__(self) -> int:
        return int(self.directions.shape[0])

    def points(
        self, sample_range: ArrayLike, hit: ArrayLike, index: ArrayLike | None = None
    ) -> tuple[NDArray[np.float64], NDArray[np.bool_], NDArray[np.int64]]:
        """Depth-buffer points (sensor frame) from the first-hit distance along each sampled ray.

        ``index`` selects the beams (of this sampler's directions) the ranges belong to.

        Returns ``(points, ok, z_d)``: NaN points where nothing lies within ``[n, f]`` in depth
        (a hit nearer than the near plane is dropped: a GPU would clip it and show what lies
        behind, which matters only within ``n`` of the sensor), and the stored ``z^d``.
        """
        cfg, cam = self.config, self.camera
        sel = np.arange(len(self)) if index is None else np.asarray(index)
        depth = np.asarray(sample_range, dtype=np.float64) / self.depth_scale[sel]
        ok = np.asarray(hit, dtype=bool) & (depth <= cfg.far) & (depth >= cfg.near)
        n = len(sel)
        z_d = np.full(n, cam.n_cd - 1, dtype=np.int64)
        z_d[ok] = np.clip(np.floor(depth_to_discrete(-depth[ok], cam)), 0, cam.n_cd - 1).astype(np.int64)  # 4.8–4.9
        pts = np.full((n, 3), np.nan)
        if np.any(ok):
            b = sel[ok]
            q_d = np.stack([self.pixels.x_d[b], self.pixels.y_d[b], z_d[ok]], axis=1)
            q_v = back_project(q_d, cam)  # 4.37–4.40, camera c's view space
            pts[ok] = np.einsum("nij,nj->ni", self._rot[b], q_v)  # 4.41–4.42, then the sensor frame
        return pts, ok, z_d

    def cast(
        self,
        caster: object,
        origins: ArrayLike,
        rotations: ArrayLike,
        cut: Cut | None = None,
    ) -> DepthBufferHits:
        """The depth-buffer point of every beam, ranging the sampled rays with ``caster``.

        ``caster``: a :class:`seatwin.engine.RayCaster` over the scene (world frame);
        ``origins`` (3,) or (N, 3): sensor position(s) in the world; ``rotations`` (3, 3) or
        (N, 3, 3): sensor → world rotation(s); ``cut``: optional per-ray range limit (e.g.
        where the ray meets the water).
        """
        n = len(self)
        o = np.broadcast_to(np.asarray(origins, dtype=np.float64), (n, 3))
        r = np.broadcast_to(np.asarray(rotations, dtype=np.float64), (n, 3, 3))
        u = np.einsum("nij,nj->ni", r, self.sample_directions)
        limit = self.config.far * self.depth_scale * (1 + 1e-6)
        if cut is not None:
            limit = np.minimum(limit, np.asarray(cut(o, u), dtype=np.float64))
        hits = caster.cast(o, u, max_range=float(limit.max()))  # type: ignore[attr-defined]
        rng = np.asarray(hits.range, dtype=np.float64)
        pts, ok, z_d = self.points(rng, (hits.object_id >= 0) & (rng <= limit))
        oid = np.where(ok, hits.object_id, -1).astype(np.int32)
        nrm = np.where(ok[:, None], hits.normal, 0).astype(np.float32)
        return DepthBufferHits(pts, np.where(ok, np.linalg.norm(np.nan_to_num(pts), axis=1), np.inf), oid, nrm, z_d)
