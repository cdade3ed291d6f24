"""The depth-buffer range model on minimal scenes, and its equivalence to rasterising."""

from __future__ import annotations

import math

import numpy as np
import pytest

from seatwin.engine import MeshData, make_caster
from seatwin.sensors.depthbuffer.errors import max_error
from seatwin.sensors.depthbuffer.filter import sensor_angles
from seatwin.sensors.depthbuffer.model import DepthBufferConfig, DepthBufferLidar
from seatwin.sensors.depthbuffer.projection import DepthCamera, depth_to_discrete, discrete_to_depth, pixel_ray, to_image_space
from seatwin.sensors.lidar_config import VLP16, LidarMount

UPRIGHT = LidarMount(z=-3.0)


def _quad(corners: list[list[float]], oid: int = 0) -> MeshData:
    return MeshData(np.asarray(corners, float), np.array([[0, 1, 2], [0, 2, 3]]), oid)


def _wall(x: float, half: float = 60.0) -> MeshData:
    """A wall facing the sensor at north = x (world NED), from 10 m below to 10 m above the water."""
    return _quad([[x, -half, -10.0], [x, half, -10.0], [x, half, 10.0], [x, -half, 10.0]])


def test_config_camera_follows_4_14_to_4_17() -> None:
    cam = DepthBufferConfig().camera()
    assert (cam.n_cw, cam.n_ch, cam.n_cd) == (4433, 3104, 2**24)
    assert math.degrees(cam.vfov_c) == pytest.approx(32.347, abs=1e-3)
    assert max_error(cam) == pytest.approx(0.0345, abs=5e-5)


def test_wall_points_within_eps_and_on_the_plane() -> None:
    caster = make_caster([_wall(40.0)])
    dirs = VLP16.with_(columns=3600).sensor_directions().astype(float)
    db = DepthBufferLidar(dirs, DepthBufferConfig())
    hits = db.cast(caster, UPRIGHT.translation, UPRIGHT.rotation())
    assert hits.hit.sum() > 1000
    exact = caster.cast(np.broadcast_to(UPRIGHT.translation, (len(dirs), 3)), dirs @ UPRIGHT.rotation().T, 100.0)
    both = hits.hit & (exact.object_id >= 0)
    p_exact = exact.range[both, None] * db.directions[both]
    d = np.linalg.norm(hits.points[both] - p_exact, axis=1)
    assert d.max() < max_error(db.camera)
    # points lie on the wall (x = 40 m in the sensor frame) up to one depth step
    cam = db.camera
    depth = -discrete_to_depth(hits.z_d[both], cam)
    step = -discrete_to_depth(hits.z_d[both] + 1, cam) - depth
    assert np.all(np.abs(hits.points[both, 0] - 40.0) <= step * 1.0001)
    assert hits.z_d.dtype.kind == "i"


def test_sampled_rays_stay_within_a_pixel_of_the_beams() -> None:
    db = DepthBufferLidar(VLP16.sensor_directions(), DepthBufferConfig())
    ang = np.arccos(np.clip(np.einsum("ij,ij->i", db.directions, db.sample_directions), -1, 1))
    cam = db.camera
    pixel = 2 * math.tan(cam.vfov_c / 2) / cam.n_ch  # angular size of a pixel at the image centre
    assert ang.max() < pixel  # ≤ half a pixel diagonal (√2/2 px), smaller off-centre
    # the legacy grid samples far off the beams at the sector edges
    legacy = DepthBufferLidar(VLP16.sensor_directions(), DepthBufferConfig(use_filter=False))
    ang_l = np.arccos(np.clip(np.einsum("ij,ij->i", legacy.directions, legacy.sample_directions), -1, 1))
    assert ang_l.max() > 100 * pixel


def test_far_plane_and_near_plane_clip() -> None:
    caster = make_caster([_wall(150.0)])
    db = DepthBufferLidar([[1.0, 0.0, 0.0]], DepthBufferConfig())
    assert not db.cast(caster, [0, 0, -3.0], UPRIGHT.rotation()).hit[0]  # beyond f = 100 m: cleared buffer
    caster = make_caster([_wall(0.02)])
    assert not db.cast(caster, [0, 0, -3.0], UPRIGHT.rotation()).hit[0]  # nearer than n = 5 cm


def test_water_cut() -> None:
    caster = make_caster([_wall(40.0)])
    db = DepthBufferLidar([[1.0, 0.0, math.tan(math.radians(-15))]], DepthBufferConfig())  # meets the water at 11.2 m
    no_cut = db.cast(caster, UPRIGHT.translation, UPRIGHT.rotation())
    assert no_cut.hit[0]
    cut = db.cast(caster, UPRIGHT.translation, UPRIGHT.rotation(), cut=lambda o, u: -o[:, 2] / np.maximum(u[:, 2], 1e-12))
    assert not cut.hit[0]


def test_legacy_rings_on_a_plane_are_polygons_fig_4_7() -> None:
    ground = _quad([[-300, -300, 0.0], [300, -300, 0.0], [300, 300, 0.0], [-300, 300, 0.0]])
    caster = make_caster([ground])
    dirs = VLP16.sensor_directions().astype(float)
    ring = np.isclose(sensor_angles(dirs)[1], math.radians(-5), atol=1e-6)
    out = {}
    for use_filter in (True, False):
        db = DepthBufferLidar(dirs[ring], DepthBufferConfig(n_c=4, use_filter=use_filter))
        h = db.cast(caster, UPRIGHT.translation, UPRIGHT.rotation())
        r = np.hypot(h.points[:, 0], h.points[:, 1])
        out[use_filter] = r.max() / r.min()
    assert out[True] == pytest.approx(1.0, abs=5e-3)  # a circle (up to half a pixel at 5° grazing: ~5 cm at 34 m)
    assert out[False] == pytest.approx(1 / math.cos(math.pi / 4), rel=0.02)  # a square: corner / side = √2


def _rasterise(tris_v: np.ndarray, cam: DepthCamera) -> np.ndarray:
    """A minimal rasteriser: screen-space edge functions at pixel centres, NDC depth interpolated
    linearly in screen space (it is affine there), nearest kept (depth test). Returns z^i (inf = empty)."""
    w, h = cam.n_cw, cam.n_ch
    xs, ys = np.meshgrid(np.arange(w) + 0.5, np.arange(h) + 0.5)
    zbuf = np.full((h, w), np.inf)
    for tri in tris_v:
        qi = to_image_space(tri, cam)
        sx, sy, sz = (qi[:, 0] + 1) * w / 2, (qi[:, 1] + 1) * h / 2, qi[:, 2]

        def edge(a: int, b: int, sx: np.ndarray = sx, sy: np.ndarray = sy) -> np.ndarray:
            return (sx[b] - sx[a]) * (ys - sy[a]) - (sy[b] - sy[a]) * (xs - sx[a])

        area = (sx[1] - sx[0]) * (sy[2] - sy[0]) - (sy[1] - sy[0]) * (sx[2] - sx[0])
        w0, w1, w2 = edge(1, 2) / area, edge(2, 0) / area, edge(0, 1) / area
        inside = (w0 >= 0) & (w1 >= 0) & (w2 >= 0)
        z = w0 * sz[0] + w1 * sz[1] + w2 * sz[2]
        closer = inside & (z < zbuf) & (z >= -1) & (z <= 1)
        zbuf[closer] = z[closer]
    return zbuf


def test_ray_through_pixel_centre_equals_rasterised_depth() -> None:
    """The model's premise: casting through pixel centres gives the rasteriser's depth buffer."""
    cam = DepthCamera(64, 48, math.radians(40.0), 0.5, 60.0)
    rng = np.random.default_rng(7)
    tris = []
    for _ in range(12):  # random triangles in front of the camera, overlapping
        c = np.array([rng.uniform(-8, 8), rng.uniform(-6, 6), -rng.uniform(8, 50)])
        tris.append(c + rng.normal(scale=6.0, size=(3, 3)) * [1, 1, 0.5])
    tris = np.asarray(tris)
    tris[..., 2] = np.minimum(tris[..., 2], -1.0)  # keep every vertex in front of the near plane
    zi_raster = _rasterise(tris, cam)
    mesh = MeshData(tris.reshape(-1, 3), np.arange(len(tris) * 3).reshape(-1, 3), 0)
    caster = make_caster([mesh])
    yy, xx = np.mgrid[0 : cam.n_ch, 0 : cam.n_cw]
    ray = pixel_ray(xx.ravel(), yy.ravel(), cam)
    s = np.linalg.norm(ray, axis=1)
    hits = caster.cast(np.zeros((len(ray), 3)), ray / s[:, None], 1e3)
    depth = hits.range.astype(float) / s
    ok = (hits.object_id >= 0) & (depth <= cam.far)
    zd_ray = np.where(ok, np.floor(depth_to_discrete(-np.where(ok, depth, 1.0), cam)), -1).reshape(cam.n_ch, cam.n_cw)
    filled = np.isfinite(zi_raster)
    zd_raster = np.where(filled, np.floor(cam.n_cd / 2 * (1 + np.where(filled, zi_raster, 0))), -1)
    # same coverage except pixel centres lying on a triangle edge (tie-breaking rules)
    assert np.mean((zd_ray >= 0) == filled) > 0.995
    both = filled & (zd_ray >= 0)
    assert both.sum() > 1000
    diff = np.abs(zd_ray[both] - zd_raster[both])
    assert np.mean(diff <= 1) > 0.995  # identical z^d up to float rounding of one level
