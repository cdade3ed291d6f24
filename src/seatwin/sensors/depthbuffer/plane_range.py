"""The ``depthbuffer-plane`` range model: the depth-buffer lidar through the real rasteriser, each
beam intersected with the surface plane of its pixel (see :mod:`.plane`).

Per sweep and per camera ``c`` of the ``N_c`` (Table 4.1's lidar, row ``lidar_eq417``: 8 cameras
of 4433 × 3104 pixels, 24-bit depth):

1. OpenGL (:class:`~seatwin.render.depthnormal.DepthNormalRenderer`, EGL; llvmpipe on a CPU)
   renders depth, normals and object ids from the sensor's pose at the time of the middle column
   of the camera's sector, through the thesis's projection 4.5 turned by ``R_y(c)`` (4.41), so
   that framebuffer pixel ``(i, j)`` is the discrete pixel ``(x^d, y^d)`` of 4.8–4.9. One
   render per sector: the thesis renders a frame; a lidar's columns are fired over a sweep.
2. Each beam — its world direction and origin at its own column's time — is projected into the
   camera (4.9); the 2 × 2 pixels around it are read back (a gather pass, not the image).
3. The pixels' points are rebuilt (4.37–4.40, pixel centres); those on a vessel are moved
   rigidly from the render time to the beam's time (the vessel's pose is known), and the beam is
   intersected with the four planes (:func:`~.plane.one_surface` decides: the nearest pixel's
   plane, or at an edge the nearest pixel's thesis point).
4. The hit is projected again from the camera's centre and steps 2–3 repeated, so that the
   sensor's motion since the render (parallax) does not pick the wrong pixels.

The beams' camera comes from the lidar's integer column grid, as in the ``depthbuffer`` model.
"""

from __future__ import annotations

import threading
from dataclasses import dataclass

import numpy as np
from numpy.typing import NDArray

from seatwin.render.depthnormal import DepthNormalRenderer
from seatwin.sensors.depthbuffer.filter import sensor_angles, split_cameras
from seatwin.sensors.depthbuffer.lidar_range import DepthBufferRanges, _fields, column_rotations, lidar_grid
from seatwin.sensors.depthbuffer.model import DepthBufferConfig
from seatwin.sensors.depthbuffer.plane import one_surface, pixel_block, pixel_points, plane_range, plane_tolerance
from seatwin.sensors.depthbuffer.projection import (
    VIEW_TO_SENSOR,
    DepthCamera,
    discrete_coordinates,
    pixel_ray,
    projection_matrix,
    rotation_y,
)
from seatwin.sensors.rangemodel import BeamBatch, RangeModel, raycast_ranges
from seatwin.world.scene import Scene


@dataclass(frozen=True)
class PlaneRanges(DepthBufferRanges):
    """:class:`DepthBufferRanges` plus which returns fell back to the thesis point (an edge)."""

    fallback: NDArray[np.bool_] | None = None


_CACHE = threading.local()
"""Each thread's renderers: a GL object lives in the context of the thread that made it (one per thread), and
must be drawn with and released on that thread."""


def renderer_for(scene: Scene, cam: DepthCamera, exclude: tuple[str, ...] = ()) -> DepthNormalRenderer:
    """The renderer of ``scene`` at ``cam``'s size (cached per thread: meshes are uploaded once per scene)."""
    renderers: dict[tuple, tuple[Scene, DepthNormalRenderer]] = _CACHE.__dict__.setdefault("renderers", {})
    key = (id(scene), cam.n_cw, cam.n_ch, tuple(sorted(exclude)))
    hit = renderers.get(key)
    if hit is None or hit[0] is not scene:
        if len(renderers) >= 2:
            for _, r in renderers.values():
                r.release()
            renderers.clear()
        hit = (scene, DepthNormalRenderer(scene, cam.n_cw, cam.n_ch, exclude=exclude))
        renderers[key] = hit
    return hit[1]


def clip_from_world(cam: DepthCamera, view_to_world: NDArray[np.float64], origin: NDArray[np.float64]) -> NDArray[np.float64]:
    """OpenGL clip-from-world matrix: the world → view transform of a camera (view space of 4.5
    turned into the world by ``view_to_world``, centre ``origin``), then the projection 4.5."""
    view = np.eye(4)
    view[:3, :3] = view_to_world.T
    view[:3, 3] = -view_to_world.T @ origin
    return projection_matrix(cam) @ view


def move_vessels(
    scene: Scene, ids: NDArray[np.int32], points: NDArray[np.float64], normals: NDArray[np.float64], t_from: float, t_to: NDArray
) -> None:
    """Move points and normals (N, K, 3) on vessels (by ``ids`` (N, K)) rigidly from the vessels'
    poses at ``t_from`` to those at each row's time ``t_to`` (N,), in place."""
    for name, vid in scene.vessel_ids.items():
        m = ids == vid
        if not m.any():
            continue
        rows = np.nonzero(m)[0]
        a, b = scene.pose(name, t_from), scene.pose(name, t_to[rows])
        dh = b.heading - float(a.heading)
        c, s = np.cos(dh), np.sin(dh)
        p = points[m]
        x, y = p[:, 0] - float(a.north), p[:, 1] - float(a.east)
        p[:, 0], p[:, 1] = c * x - s * y + b.north, s * x + c * y + b.east
        points[m] = p
        q = normals[m]
        q[:, 0], q[:, 1] = c * q[:, 0] - s * q[:, 1], s * q[:, 0] + c * q[:, 1]
        normals[m] = q


@dataclass
class _Look:
    """Per beam, what its 2 × 2 pixels say (world frame)."""

    range: NDArray[np.float64]  # the nearest pixel's plane along the beam
    one: NDArray[np.bool_]  # the four pixels are one plane
    surface: NDArray[np.bool_]  # the nearest pixel holds a surface
    point: NDArray[np.float64]  # the nearest pixel's point
    normal: NDArray[np.float64]
    object_id: NDArray[np.int32]


def _look(
    renderer: DepthNormalRenderer,
    scene: Scene,
    cam: DepthCamera,
    view_to_world: NDArray[np.float64],
    centre: NDArray[np.float64],
    t_render: float,
    view: NDArray[np.float64],
    origins: NDArray[np.float64],
    directions: NDArray[np.float64],
    times: NDArray[np.float64],
    linear: bool,
) -> _Look:
    """Read the pixels around view-space vectors ``view`` and intersect the beams with their planes."""
    n = len(view)
    front = view[:, 2] < 0
    q = discrete_coordinates(np.where(front[:, None], view, [0.0, 0.0, -1.0]), cam)  # 4.9
    blk = pixel_block(q[:, 0], q[:, 1], cam)
    got = renderer.sample(blk.x.ravel(), blk.y.ravel())
    win, ids = got.window.reshape(n, 4), got.object_id.reshape(n, 4)
    nrm = got.normal.reshape(n, 4, 3).astype(np.float64)
    has = (win < 1.0) & (ids >= 0)
    ids = np.where(has, ids, -1).astype(np.int32)
    if linear:  # the float32 view depth, through the pixel centres
        p_view = pixel_ray(blk.x, blk.y, cam) * np.where(has, got.linear.reshape(n, 4), 1.0)[..., None]
    else:  # the 24-bit depth buffer, 4.37–4.40 at the pixel centres
        p_view = pixel_points(blk.x, blk.y, np.where(has, win, 0.5), cam)
    pts = centre + p_view @ view_to_world.T
    move_vessels(scene, ids, pts, nrm, t_render, times)
    t = np.where(has, plane_range(origins[:, None], directions[:, None], pts, nrm), np.nan)
    k = blk.nearest
    rows = np.arange(n)
    depth = -p_view[rows, k, 2]
    one = front & one_surface(t, ids, plane_tolerance(depth, cam))
    return _Look(t[rows, k], one, front & has[rows, k], pts[rows, k], nrm[rows, k], ids[rows, k])


def plane_ranges(
    scene: Scene, batch: BeamBatch, config: DepthBufferConfig = DepthBufferConfig(), linear_depth: bool = True
) -> PlaneRanges:
    """Ranges of a batch of beams by plane intersection in rasterised depth buffers (module doc).

    ``linear_depth``: rebuild the pixels' points from the float32 view depth rendered besides the
    depth buffer (default), or from the 24-bit depth buffer itself (4.37–4.40), whose float32
    rasterisation near the far plane is off by up to ±2 levels (±2.4 cm at 100 m)."""
    n = len(batch)
    if n == 0:
        res0 = raycast_ranges(scene, batch)
        return PlaneRanges(**_fields(res0), sensor_points=np.zeros((0, 3), np.float32), fallback=np.zeros(0, bool))
    cam, n_c = config.camera(), config.n_c
    renderer = renderer_for(scene, cam, tuple(batch.exclude))
    grid = lidar_grid(batch.lidar_directions, batch.rings)
    if grid is not None:
        cam_of = grid.cameras(n_c)[batch.beam]
    else:
        cam_of = split_cameras(sensor_angles(batch.sensor_directions)[0], n_c)[0]
    per_sweep = len(batch.lidar_directions) // batch.rings
    group = (batch.column // per_sweep) * n_c + cam_of
    rot = column_rotations(batch)
    u = batch.directions.astype(np.float64)
    u /= np.linalg.norm(u, axis=1, keepdims=True)
    o = batch.origins.astype(np.float64)
    t_beam = batch.column_times[batch.column]
    limit = batch.max_range.astype(np.float64)
    reach = float(limit.max())  # the lidar's own range (the sampled pixel ray is not cut at the water: nothing below is drawn)
    rng = np.full(n, np.inf)
    pts = np.full((n, 3), np.nan)
    nrm = np.zeros((n, 3), np.float32)
    oid = np.full(n, -1, np.int32)
    fallback = np.zeros(n, bool)
    for g in np.unique(group):
        idx = np.flatnonzero(group == g)
        mid = idx[len(idx) // 2]
        col = batch.column[mid]
        m_g = rot[mid] @ VIEW_TO_SENSOR @ rotation_y(cam_of[mid], n_c)
        c_g, t_g = np.asarray(batch.column_origins[col], np.float64), float(batch.column_times[col])
        axis = -m_g[:, 2]  # the camera looks along −z (view space of 4.5)
        renderer.render(clip_from_world(cam, m_g, c_g), t_g, (*axis, -float(axis @ c_g)))
        ob, ub, tb = o[idx], u[idx], t_beam[idx]
        first = _look(renderer, scene, cam, m_g, c_g, t_g, ub @ m_g, ob, ub, tb, linear_depth)
        seen = np.isfinite(first.range) & first.one
        view = np.where(seen[:, None], (ob + np.nan_to_num(first.range)[:, None] * ub - c_g) @ m_g, ub @ m_g)
        look = _look(
            renderer, scene, cam, m_g, c_g, t_g, view, ob, ub, tb, linear_depth
        )  # the hit seen from the camera (parallax)
        plane = look.one & (look.range <= limit[idx])
        r_fb = np.linalg.norm(look.point - ob, axis=1)
        back = ~look.one & look.surface & (r_fb <= reach)
        got = plane | back
        rng[idx] = np.where(plane, look.range, np.where(back, r_fb, np.inf))
        hit_w = np.where(plane[:, None], ub * np.nan_to_num(look.range)[:, None], look.point - ob)
        pts[idx] = np.where(got[:, None], np.einsum("nji,nj->ni", rot[idx], hit_w), np.nan)  # world → sensor (Rᵀ)
        nrm[idx] = np.where(got[:, None], look.normal, 0.0)
        oid[idx] = np.where(got, look.object_id, -1)
        fallback[idx] = back
    return PlaneRanges(
        range=rng.astype(np.float32), object_id=oid, normal=nrm, sensor_points=pts.astype(np.float32), fallback=fallback
    )


def make_plane_range_model(config: DepthBufferConfig) -> RangeModel:
    """A ``depthbuffer-plane`` range model with fixed depth-buffer parameters."""

    def model(scene: Scene, batch: BeamBatch) -> PlaneRanges:
        return plane_ranges(scene, batch, config)

    return model


plane_range_model: RangeModel = make_plane_range_model(DepthBufferConfig())
"""``range_model="depthbuffer-plane"``: Table 4.1's lidar (row lidar_eq417), rasterised, plane intersection."""
