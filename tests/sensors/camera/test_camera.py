"""The camera rig: intrinsics and plumb-bob (hand values), mounts, CameraInfo, and labels against ground truth."""

from __future__ import annotations

import math

import numpy as np
import pytest

from seatwin.errors import ParameterError
from seatwin.geo import yaw_matrix
from seatwin.render import SceneRenderer
from seatwin.scenario.builtin import builtin_scenario
from seatwin.sensors.camera import (
    CameraConfig,
    DistortionMap,
    camera_info_fields,
    distort,
    focal_from_hfov,
    ground_truth_boxes,
    intrinsic_matrix,
    project,
    rig_mounts,
    undistort,
)
from seatwin.sensors.camera.intrinsics import vfov_deg
from seatwin.sensors.camera.labels import truncation, vessel_box
from seatwin.world.scene import Scene


def test_focal_length_and_vfov_hand_values() -> None:
    assert focal_from_hfov(612, 82.0) == pytest.approx(306.0 / math.tan(math.radians(41.0)))
    assert focal_from_hfov(612, 82.0) == pytest.approx(352.013, abs=1e-3)
    # thesis Eq. 4.3: tan(VFOV/2) = (H/W) tan(HFOV/2)
    assert math.tan(math.radians(vfov_deg(612, 512, 82.0)) / 2) == pytest.approx(512 / 612 * math.tan(math.radians(41.0)))
    k = intrinsic_matrix(612, 512, 82.0)
    assert k[0, 2] == 305.5 and k[1, 2] == 255.5 and k[0, 0] == k[1, 1]


def test_plumb_bob_hand_values_and_inverse() -> None:
    xd, yd = distort(0.1, 0.2, (0.1, 0.0, 0.0, 0.0, 0.0))
    assert (float(xd), float(yd)) == pytest.approx((0.1 * 1.005, 0.2 * 1.005))
    xd, yd = distort(0.1, 0.2, (0.0, 0.0, 0.01, 0.02, 0.0))  # tangential: r² = 0.05
    assert float(xd) == pytest.approx(0.1 + 2 * 0.01 * 0.02 + 0.02 * (0.05 + 0.02))
    assert float(yd) == pytest.approx(0.2 + 0.01 * (0.05 + 0.08) + 2 * 0.02 * 0.02)
    d = (-0.25, 0.08, 0.001, -0.002, 0.01)
    x, y = np.meshgrid(np.linspace(-0.8, 0.8, 9), np.linspace(-0.6, 0.6, 7))
    xu, yu = undistort(*distort(x, y, d), d)
    np.testing.assert_allclose(xu, x, atol=1e-7)
    np.testing.assert_allclose(yu, y, atol=1e-7)


def test_distortion_map_zero_is_identity_and_moves_pixels_otherwise() -> None:
    k = intrinsic_matrix(64, 48, 82.0)
    img = np.random.default_rng(1).integers(0, 255, (48, 64, 3), dtype=np.uint8)
    assert (DistortionMap.build(k, (0, 0, 0, 0, 0), 64, 48).apply(img) == img).all()
    m = DistortionMap.build(k, (-0.3, 0.0, 0.0, 0.0, 0.0), 64, 48)
    out = m.apply(img)
    assert (out[24, 32] == img[24, 32]).all() or abs(int(out[24, 32, 0]) - int(img[24, 32, 0])) < 40  # centre stays
    assert not (out == img).all()
    # a point's distorted projection lands where the map samples it from
    u, v = project([[0.5, 0.3, 1.0]], k, (-0.3, 0, 0, 0, 0))[0]
    src = m.nearest[int(round(v)) * 64 + int(round(u))]
    pu, pv = project([[0.5, 0.3, 1.0]], k)[0]
    assert abs(src % 64 - pu) <= 1.0 and abs(src // 64 - pv) <= 1.0


def test_rig_mounts_thesis_layout() -> None:
    cfg = CameraConfig()
    mounts = {m.name: m for m in rig_mounts(cfg)}
    assert list(mounts) == ["left", "front", "right"]
    c15, s15 = math.cos(math.radians(15)), math.sin(math.radians(15))
    # optical z (the axis) in the body FRD frame: forward, pitched 15° down (z down positive)
    np.testing.assert_allclose(mounts["front"].rotation @ [0, 0, 1], [c15, 0, s15], atol=1e-12)
    np.testing.assert_allclose(
        mounts["left"].rotation @ [0, 0, 1],
        [c15 * math.cos(math.radians(72)), -c15 * math.sin(math.radians(72)), s15],
        atol=1e-12,
    )
    np.testing.assert_allclose(mounts["front"].rotation @ [1, 0, 0], [0, 1, 0], atol=1e-12)  # optical x → starboard
    assert mounts["front"].translation[2] == -cfg.height_m
    info = camera_info_fields(cfg)
    assert info.distortion_model == "plumb_bob" and len(info.d) == 5
    np.testing.assert_allclose(info.p[:, :3], info.k)
    np.testing.assert_allclose(info.p[:, 3], 0)
    with pytest.raises(ParameterError):
        CameraConfig(names=("a", "b"), azimuths_deg=(0.0,))


def test_truncation_and_box_of_a_cube() -> None:
    assert truncation([0, 0, 10, 10], [0, 0, 5, 10]) == pytest.approx(0.5)
    k = intrinsic_matrix(612, 512, 82.0)
    # a 2 m cube 20 m ahead of a camera looking north (optical z = north, x = east, y = down)
    rot = np.array([[0.0, 0.0, 1.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]])
    v = np.array([[20 + a, b, -c] for a in (-1, 1) for b in (-1, 1) for c in (0, 2)], float)
    edges = np.array([[i, j] for i in range(8) for j in range(i + 1, 8)])
    full, inside = vessel_box(v, edges, rot, [0, 0, -1.0], k, None, 612, 512)
    f = k[0, 0]
    assert full[0] == pytest.approx(305.5 - f * 1 / 19) and full[2] == pytest.approx(305.5 + f * 1 / 19)
    assert full[1] == pytest.approx(255.5 - f * 1 / 19) and full[3] == pytest.approx(255.5 + f * 1 / 19)
    np.testing.assert_allclose(full, inside)


@pytest.fixture(scope="module")
def rig(camera_rig: tuple) -> tuple:
    return camera_rig


def _labels_at(rig: tuple, t: float) -> list:
    sc, scene, cfg, info, r = rig
    p = scene.pose(sc.ownship.name, t)
    out = []
    for m in rig_mounts(cfg):
        rot, c = m.world_pose(float(p.north), float(p.east), float(p.heading))
        targets = [n for n in scene.vessel_names if n != sc.ownship.name] + list(scene.moored_boats)
        f = r.render(t, rot, c, solo=targets)
        labels = ground_truth_boxes(
            scene, t, rot, c, info.k, None, cfg.width, cfg.height, f.ids, f.unoccluded, exclude=(sc.ownship.name,)
        )
        out.append((m, rot, c, f, labels))
    return out


def test_labels_match_boxes_projected_from_ground_truth(rig: tuple) -> None:
    sc, scene, cfg, info, r = rig
    checked = 0
    for dt in (20.0, 40.0, 60.0):
        t = sc.start + dt
        for _m, rot, c, f, labels in _labels_at(rig, t):
            for b in labels:
                if b.instance in scene.moored_boats:
                    continue  # test_every_vessel_labelled.py checks those
                # independent: the vessel's corners posed from the scenario's own state, projected by K
                st = next(v for v in sc.vessels if v.name == b.instance).trajectory.state_at(t)
                verts = np.asarray(scene.vessel_models[b.instance].mesh.vertices, float)
                world = verts @ yaw_matrix(float(st.heading)).T + [float(st.north), float(st.east), 0.0]
                world = world[world[:, 2] <= 0]  # what floats above the water
                uv = project((world - c) @ rot, info.k)
                if b.truncation == 0.0:
                    assert b.x_min == pytest.approx(uv[:, 0].min(), abs=1.0)
                    assert b.x_max == pytest.approx(uv[:, 0].max(), abs=1.0)
                    assert b.y_min == pytest.approx(uv[:, 1].min(), abs=1.0)
                # …and the rendered pixels of the vessel lie in its box (within the rasteriser's half pixel)
                ys, xs = np.nonzero(f.ids == b.object_id)
                if len(xs):
                    assert xs.min() >= b.x_min - 1 and xs.max() <= b.x_max + 1
                    assert ys.min() >= b.y_min - 1 and ys.max() <= b.y_max + 1
                    if b.visible_fraction == 1.0 and b.truncation == 0.0:
                        assert xs.min() == pytest.approx(b.x_min, abs=1.5) and xs.max() == pytest.approx(b.x_max, abs=1.5)
                        assert ys.max() == pytest.approx(b.y_max, abs=1.5)
                assert b.visible_pixels == len(xs)
                checked += 1
    assert checked >= 3


@pytest.mark.slow
def test_occlusion_and_truncation_are_measured() -> None:
    sc = builtin_scenario("surprise_separation")  # the targets come in line, one hiding the other
    scene = Scene.from_scenario(sc)
    cfg = CameraConfig()
    info = camera_info_fields(cfg)
    r = SceneRenderer(scene, info.k, cfg.width, cfg.height, exclude=[sc.ownship.name])
    rig = (sc, scene, cfg, info, r)
    fractions, truncs = [], []
    for t in np.arange(sc.start, sc.end, 4.0):
        for _m, _rot, _c, f, labels in _labels_at(rig, float(t)):
            for b in labels:
                fractions.append(b.visible_fraction)
                truncs.append(b.truncation)
                assert b.visible_fraction == pytest.approx(min(b.visible_pixels / f.unoccluded[b.instance], 1.0))
    assert min(fractions) < 0.9  # one target hides the other at some point
    assert max(fractions) == 1.0
    assert all(0.0 <= x <= 1.0 for x in truncs) and max(truncs) > 0.05  # boxes cut at the image edge too


def test_distorted_labels_match_the_distorted_vessel_pixels(rig: tuple) -> None:
    sc, scene, cfg, info, r = rig
    d = (-0.25, 0.08, 0.0, 0.0, 0.0)
    dmap = DistortionMap.build(info.k, d, cfg.width, cfg.height)
    t = sc.start + 40.0
    p = scene.pose(sc.ownship.name, t)
    rot, c = {m.name: m for m in rig_mounts(cfg)}["right"].world_pose(float(p.north), float(p.east), float(p.heading))
    f = r.render(t, rot, c, solo=["Havfruen", "Finn"])
    labels = ground_truth_boxes(
        scene, t, rot, c, info.k, d, cfg.width, cfg.height, f.ids, f.unoccluded, exclude=(sc.ownship.name,)
    )
    ids_d = dmap.apply_nearest(f.ids)
    b = next(x for x in labels if x.instance == "Havfruen")
    ys, xs = np.nonzero(ids_d == b.object_id)
    # pixel centres inside the projected outline, resampled to the nearest pinhole pixel: within 2 px
    assert abs(xs.min() - b.x_min) <= 2.0 and abs(xs.max() - b.x_max) <= 2.0
    assert abs(ys.min() - b.y_min) <= 2.0 and abs(ys.max() - b.y_max) <= 2.0
    plain = next(x for x in _labels_at(rig, t)[2][4] if x.instance == "Havfruen")
    assert abs(plain.x_min - b.x_min) > 2  # the distortion moved the box
