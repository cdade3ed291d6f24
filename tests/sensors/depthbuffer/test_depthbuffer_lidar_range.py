"""The ``depthbuffer`` range model plugged into the lidar pipeline (``Lidar(range_model="depthbuffer")``)."""

from __future__ import annotations

import numpy as np
import pytest

from seatwin.engine import make_caster
from seatwin.scenario.model import Trajectory
from seatwin.sensors.depthbuffer.lidar_range import DepthBufferRanges, column_rotations, depthbuffer_ranges
from seatwin.sensors.depthbuffer.model import DepthBufferConfig, DepthBufferLidar
from seatwin.sensors.depthbuffer.verify import verification_scene
from seatwin.sensors.lidar import Lidar
from seatwin.sensors.lidar_config import VLP16, LidarMount
from seatwin.sensors.rangemodel import get_range_model, raycast_ranges
from seatwin.world.harbour import build_harbour
from seatwin.world.scene import Scene
from seatwin.world.vessels import vessel_model


@pytest.fixture(scope="module")
def scene() -> Scene:
    return verification_scene()


def test_registered_as_depthbuffer() -> None:
    from seatwin.sensors import depthbuffer

    assert get_range_model("depthbuffer") is depthbuffer.range_model


@pytest.mark.parametrize("drop", [0.0, 0.8, 0.97])
def test_column_rotations_recover_the_sensor_pose(drop: float) -> None:
    own = Trajectory(np.array([0.0, 10.0]), np.array([0.0, 30.0]), np.array([0.0, 5.0]), np.radians([10.0, 40.0]))
    sc = Scene(build_harbour("none"), {"own": (vessel_model("milliampere"), own)})
    mount = LidarMount(z=-3.0, yaw_deg=57.3, roll_deg=180.0)  # milliAmpere's upside-down VLP-16
    lid = Lidar(sc, VLP16.with_(drop_probability=drop), mount, platform="own")
    b = lid.beams(2.0, 3)
    r = column_rotations(b)
    np.testing.assert_allclose(np.einsum("nij,nj->ni", r, b.sensor_directions), b.directions, atol=2e-6)
    np.testing.assert_allclose(np.einsum("nij,nkj->nik", r, r), np.broadcast_to(np.eye(3), r.shape), atol=1e-9)
    # against the truth: heading at each column's time, then the mount
    head = sc.pose("own", b.column_times).heading[b.column]
    c, s = np.cos(head), np.sin(head)
    rz = np.zeros((len(head), 3, 3))
    rz[:, 0, 0], rz[:, 0, 1], rz[:, 1, 0], rz[:, 1, 1], rz[:, 2, 2] = c, -s, s, c, 1
    truth = np.einsum("nij,jk->nik", rz, mount.rotation())
    assert np.abs(r - truth).max() < (1e-5 if drop < 0.9 else 5e-3)  # one-beam columns borrow a neighbour's


def test_range_model_matches_the_snapshot_model(scene: Scene) -> None:
    """Through the pipeline's batches (vessels posed per column) the points equal a frozen-scene cast."""
    mount = LidarMount(z=-3.0, yaw_deg=30.0)
    lid = Lidar(scene, VLP16.with_(drop_probability=0.0, columns=900), mount)
    b = lid.beams(1.0, 0)
    res = depthbuffer_ranges(scene, b)
    assert isinstance(res, DepthBufferRanges) and res.sensor_points.shape == (len(b), 3)
    db = DepthBufferLidar(b.lidar_directions, DepthBufferConfig())
    caster = make_caster(scene.posed_meshes(1.0))
    from seatwin.sensors.lidar_physics import water_limit

    snap = db.cast(
        caster,
        mount.translation,
        mount.rotation(),
        cut=lambda o, u: water_limit(o[:, 2].astype(np.float32), u[:, 2].astype(np.float32), 100.0),
    )
    hit = res.object_id >= 0
    assert (hit != snap.hit[b.beam]).sum() <= 2  # float32 ties at silhouettes
    both = hit & snap.hit[b.beam]
    assert both.sum() > 500
    np.testing.assert_allclose(res.sensor_points[both], snap.points[b.beam][both], atol=2e-3)
    np.testing.assert_allclose(res.range[both], np.linalg.norm(res.sensor_points[both], axis=1), rtol=1e-6)


def test_lidar_sweep_with_depthbuffer_close_to_raycast(scene: Scene) -> None:
    cfg = VLP16.with_(drop_probability=0.0, range_accuracy=0.0, columns=900)
    mount = LidarMount(z=-3.0)
    a = Lidar(scene, cfg, mount, range_model="raycast").sweep(1.0, 0)
    d = Lidar(scene, cfg, mount, range_model="depthbuffer").sweep(1.0, 0)
    assert abs(len(a) - len(d)) < 0.02 * len(a)
    b = Lidar(scene, cfg, mount).beams(1.0, 0)
    rc = raycast_ranges(scene, b)
    db = depthbuffer_ranges(scene, b)
    both = (rc.object_id >= 0) & (db.object_id >= 0) & (rc.object_id == db.object_id)
    err = np.abs(db.range[both] - rc.range[both])
    assert np.percentile(err, 99) < DepthBufferConfig().camera().far * 1e-3


def test_empty_batch(scene: Scene) -> None:
    lid = Lidar(scene, VLP16.with_(drop_probability=1.0), LidarMount(z=-3.0))
    res = depthbuffer_ranges(scene, lid.beams(1.0, 0))
    assert len(res.range) == 0 and res.sensor_points.shape == (0, 3)


def test_lidar_sweep_keeps_the_depth_buffers_points(scene: Scene) -> None:
    """The pipeline places depth-buffer points where the pixel ray put them (its direction
    error included), not along the beam at the back-projected range."""
    cfg = VLP16.with_(drop_probability=0.0, range_accuracy=0.0, columns=900)
    mount = LidarMount(z=-3.0)
    lid = Lidar(scene, cfg, mount, range_model="depthbuffer", self_returns=False)
    sweep = lid.sweep(1.0, 0)
    res = depthbuffer_ranges(scene, lid.beams(1.0, 0))
    ok = np.flatnonzero(res.object_id >= 0)
    assert len(sweep) == ok.size > 500
    np.testing.assert_allclose(sweep.xyz, res.sensor_points[ok], atol=1e-4)
    along_beam = res.range[ok, None] * lid.d_sensor[ok]
    assert np.abs(along_beam - res.sensor_points[ok]).max() > 1e-3


def test_lidar_columns_on_camera_boundaries_take_the_integer_grid() -> None:
    from seatwin.sensors.depthbuffer.lidar_range import lidar_grid, sampler_for
    from seatwin.sensors.lidar_config import VLP16_THESIS

    # 1024 columns and 8 cameras: every 64th column lies exactly on a boundary between two cameras.
    dirs = VLP16_THESIS.sensor_directions()
    db = sampler_for(DepthBufferConfig(), dirs, VLP16_THESIS.rings)
    assert db.grid is not None
    assert np.array_equal(db.pixels.camera, db.grid.cameras(8))
    assert np.bincount(db.pixels.camera).tolist() == [128 * VLP16_THESIS.rings] * 8
    assert lidar_grid(np.ascontiguousarray(dirs[::-1]), VLP16_THESIS.rings) is None  # not the lidar's column layout
    assert lidar_grid(dirs, 5) is None
